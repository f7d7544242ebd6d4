"""SDF world tools: resolve and flatten includes, check a world, slice it into a map.

Include rule (the simulator's core applies the same one to the worlds it loads; a test holds the two equal):
  model://NAME[/rest]  -> the first folder NAME in GAZEBO_MODEL_PATH (':'-separated, in order), then car's models/
  package://PKG/rest   -> PKG's folder found through ROS_PACKAGE_PATH
  file://PATH, PATH    -> absolute, or relative to the including file's folder
A folder is a model folder: its model.config names the SDF file (the highest <sdf version> up to 1.9).
"""
from __future__ import annotations

import copy
import math
import os
import sys
import xml.etree.ElementTree as ET

import numpy as np

KNOWN_GEOMETRY = {'box', 'cylinder', 'sphere', 'plane', 'mesh', 'capsule', 'ellipsoid', 'heightmap', 'image',
                  'polyline', 'empty'}
SIMULATED_GEOMETRY = {'box', 'cylinder', 'sphere', 'plane'}


class WorldError(Exception):
    """A world that cannot be used. str() reads 'FILE: ELEMENT: REASON'."""

    def __init__(self, file: str, element: str, reason: str):
        self.file, self.element, self.reason = file, element, reason
        super().__init__('%s: %s: %s' % (file, element, reason) if element else '%s: %s' % (file, reason))


# ---- URIs and model folders ---------------------------------------------------------------------------

def model_path() -> list:
    """Where model:// looks, in order (the core's rule: GAZEBO_MODEL_PATH, then car's models/)."""
    from car import _core
    return _core.model_path()


def resolve_uri(uri: str, base_dir: str) -> str | None:
    """A file or folder for a URI, or None when nothing matches: the core's rule (car_sim::resolve_uri), so the
    world tools and the simulator resolve every URI the same way."""
    from car import _core
    return _core.resolve_uri(uri, base_dir) or None


def model_sdf_file(folder: str) -> str:
    """The SDF file a model folder's model.config names (highest version <= 1.9)."""
    cfg = os.path.join(folder, 'model.config')
    if not os.path.isfile(cfg):
        raise WorldError(folder, 'model.config', 'a model folder needs a model.config')
    best, best_v = None, -1.0
    for e in parse_file(cfg).getroot().findall('sdf'):
        try:
            v = float(e.get('version', '0'))
        except ValueError:
            v = 0.0
        if v <= 1.9 and v > best_v and (e.text or '').strip():
            best, best_v = e.text.strip(), v
    if best is None:
        raise WorldError(cfg, 'model/sdf', 'names no SDF file')
    return os.path.join(folder, best)


# ---- poses --------------------------------------------------------------------------------------------

def parse_pose(text: str | None, file: str, element: str) -> np.ndarray:
    """4x4 transform of 'x y z roll pitch yaw'; an empty pose is identity."""
    vals = (text or '').split()
    if not vals:
        return np.eye(4)
    try:
        nums = [float(v) for v in vals]
    except ValueError:
        nums = []
    if len(nums) != 6:
        raise WorldError(file, element, "pose '%s' is not 6 numbers (x y z roll pitch yaw)" % (text or '').strip())
    x, y, z, r, p, yw = nums
    if not all(math.isfinite(v) for v in (x, y, z, r, p, yw)):
        raise WorldError(file, element, "pose '%s' has a non-finite value" % text.strip())
    cr, sr, cp, sp, cy, sy = math.cos(r), math.sin(r), math.cos(p), math.sin(p), math.cos(yw), math.sin(yw)
    T = np.eye(4)
    T[:3, :3] = [[cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
                 [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
                 [-sp, cp * sr, cp * cr]]
    T[:3, 3] = (x, y, z)
    return T


def format_pose(T: np.ndarray) -> str:
    R = T[:3, :3]
    pitch = math.asin(max(-1.0, min(1.0, -R[2, 0])))
    roll, yaw = math.atan2(R[2, 1], R[2, 2]), math.atan2(R[1, 0], R[0, 0])
    vals = list(T[:3, 3]) + [roll, pitch, yaw]
    return ' '.join(repr(float('%.12g' % v)) if v else '0' for v in vals)


def _set_child(e: ET.Element, tag: str, text: str) -> None:
    c = e.find(tag)
    if c is None:
        c = ET.SubElement(e, tag)
    c.text = text


# ---- flatten ------------------------------------------------------------------------------------------

def _absolute_mesh_uris(elem: ET.Element, base_dir: str) -> None:
    """Mesh URIs inside an included model, made absolute so the output stands alone."""
    for mesh in elem.iter('mesh'):
        u = mesh.find('uri')
        if u is not None and u.text and not u.text.strip().startswith('package://'):
            p = resolve_uri(u.text, base_dir)
            if p:
                u.text = 'file://' + os.path.abspath(p)


def _load_included(include: ET.Element, base_dir: str, file: str, where: str) -> tuple:
    uri_e = include.find('uri')
    if uri_e is None or not (uri_e.text or '').strip():
        raise WorldError(file, where, '<include> has no <uri>')
    uri = uri_e.text.strip()
    target = resolve_uri(uri, base_dir)
    if target is None:
        raise WorldError(file, where + '/uri', "cannot find '%s' (model path: %s)" % (uri, ':'.join(model_path())))
    sdf_file = model_sdf_file(target) if os.path.isdir(target) else target
    try:
        root = parse_file(sdf_file).getroot()
    except ET.ParseError as e:
        raise WorldError(sdf_file, '', 'malformed XML: %s' % e)
    body = next((c for c in root if c.tag in ('model', 'light', 'actor')), None)
    if body is None:
        raise WorldError(sdf_file, 'sdf', 'holds no <model> or <light>')
    return copy.deepcopy(body), os.path.dirname(sdf_file), sdf_file


def _expand(parent: ET.Element, base_dir: str, file: str, where: str, depth: int = 0) -> None:
    """Replaces every <include> below parent by what it includes, with the include's overrides."""
    if depth > 32:
        raise WorldError(file, where, 'includes nest deeper than 32 levels (a cycle?)')
    for i, child in enumerate(list(parent)):
        if child.tag == 'include':
            here = '%s/include[%d]' % (where, i)
            body, body_dir, body_file = _load_included(child, base_dir, file, here)
            name = child.findtext('name')
            if name:
                body.set('name', name.strip())
            pose = child.find('pose')
            if pose is not None:
                parse_pose(pose.text, file, here + '/pose')
                _set_child(body, 'pose', pose.text.strip())
            static = child.findtext('static')
            if static is not None and body.tag == 'model':
                _set_child(body, 'static', static.strip())
            _absolute_mesh_uris(body, body_dir)
            _expand(body, body_dir, body_file, '%s[%s]' % (body.tag, body.get('name')), depth + 1)
            idx = list(parent).index(child)
            parent.remove(child)
            parent.insert(idx, body)
        elif child.tag == 'model':
            _expand(child, base_dir, file, '%s/model[%s]' % (where, child.get('name')), depth)


def _hoist_nested(world: ET.Element) -> None:
    """Nested models become top-level models 'parent::child' with composed poses (the core does the same)."""
    changed = True
    while changed:
        changed = False
        for m in list(world.findall('model')):
            for n in list(m.findall('model')):
                Tm = parse_pose(m.findtext('pose'), '', '')
                Tn = parse_pose(n.findtext('pose'), '', '')
                n.set('name', '%s::%s' % (m.get('name'), n.get('name')))
                _set_child(n, 'pose', format_pose(Tm @ Tn))
                if (m.findtext('static') or '').strip() in ('1', 'true'):
                    _set_child(n, 'static', 'true')
                m.remove(n)
                world.insert(list(world).index(m) + 1, n)
                changed = True


def _apply_state(world: ET.Element) -> None:
    """Gazebo applies a world's <state> when it loads: model poses there win; the block is then dropped."""
    for state in world.findall('state'):
        for sm in state.findall('model'):
            pose = sm.findtext('pose')
            for m in world.findall('model'):
                if m.get('name') == sm.get('name') and pose is not None:
                    _set_child(m, 'pose', pose.strip())
        world.remove(state)


def parse_file(path: str) -> ET.ElementTree:
    """ET.parse, but the file is fed to expat in one piece: ET.parse feeds 64 kB at a time, and expat (2.5)
    rescans a token that spans the pieces from its start each time, so a 50 MB comment took minutes (quadratic)
    instead of a fraction of a second."""
    with open(path, 'rb') as f:
        data = f.read()
    parser = ET.XMLParser(target=ET.TreeBuilder())
    parser.feed(data)
    return ET.ElementTree(parser.close())


def flatten(path: str) -> ET.ElementTree:
    """One self-contained world: includes resolved and replaced, nested models hoisted, <state> applied."""
    try:
        tree = parse_file(path)
    except FileNotFoundError:
        raise WorldError(path, '', 'no such file')
    except ET.ParseError as e:
        raise WorldError(path, '', 'malformed XML: %s' % e)
    root = tree.getroot()
    if root.tag != 'sdf':
        raise WorldError(path, root.tag, 'root element is not <sdf>')
    world = root.find('world')
    if world is None:
        raise WorldError(path, 'sdf', 'no <world>')
    where = 'world[%s]' % world.get('name')
    try:
        _expand(world, os.path.dirname(os.path.abspath(path)), path, where)
        _hoist_nested(world)
        _apply_state(world)
        ET.indent(tree, space='  ')
    except RecursionError:
        raise WorldError(path, where, 'elements nest too deep to read (more than %d levels)' % sys.getrecursionlimit())
    return tree


def flatten_to_string(path: str) -> str:
    return "<?xml version='1.0'?>\n" + ET.tostring(flatten(path).getroot(), encoding='unicode') + '\n'


# ---- check --------------------------------------------------------------------------------------------

def _finding(severity, code, element, message):
    return {'severity': severity, 'code': code, 'element': element, 'message': message, 'line': 0}


def _xml_findings(world: ET.Element, file: str) -> list:
    """What can be seen in the flattened XML: poses that do not parse, unknown or unsimulated geometry, meshes
    without a uri."""
    out = []
    where_world = 'world[%s]' % world.get('name')

    def walk(e, path):
        for i, c in enumerate(e):
            name = c.get('name')
            here = '%s/%s' % (path, '%s[%s]' % (c.tag, name) if name else c.tag)
            if c.tag == 'pose':
                try:
                    parse_pose(c.text, file, here)
                except WorldError as err:
                    out.append(_finding('error', 'pose-malformed', here, err.reason))
            elif c.tag == 'geometry':
                kids = [g for g in c if isinstance(g.tag, str)]
                if not kids:
                    out.append(_finding('error', 'geometry-empty', here, '<geometry> holds no shape'))
                for g in kids:
                    if g.tag not in KNOWN_GEOMETRY:
                        out.append(_finding('error', 'geometry-unknown', here + '/' + g.tag,
                                            'unknown geometry <%s> (SDF knows %s)' % (g.tag,
                                                                                     ', '.join(sorted(KNOWN_GEOMETRY)))))
                    elif g.tag == 'mesh' and not (g.findtext('uri') or '').strip():
                        out.append(_finding('error', 'uri-missing', here + '/mesh', '<mesh> has no <uri>'))
                    elif g.tag not in SIMULATED_GEOMETRY and g.tag != 'mesh':
                        out.append(_finding('warning', 'geometry-unsimulated', here + '/' + g.tag,
                                            '<%s> is not simulated by car; ignored' % g.tag))
                continue
            if c.tag in ('state', 'gui', 'plugin'):
                continue
            walk(c, here)

    walk(world, where_world)
    return out


def check(path: str, inertia_tolerance: float = 0.10) -> dict:
    """The model check's physics-aware checks for every link of a world, plus what only worlds have. A report
    like check_model's: {'source', 'findings', 'counts'}."""
    from car import _core, model_check
    findings = []
    plugins = []  # the plug-ins of world models simulated as robots
    try:
        tree = flatten(path)
    except WorldError as e:
        findings.append(_finding('error', 'world-unreadable', e.element, e.reason))
        tree = None
    if tree is not None:
        world = tree.getroot().find('world')
        findings += _xml_findings(world, path)
        if not any(f['severity'] == 'error' for f in findings):
            xml = ET.tostring(tree.getroot(), encoding='unicode')
            try:
                desc = _core.load_world_string(xml, path)
            except ValueError as e:
                findings.append(_finding('error', 'world-load', '', str(e).split(': ', 1)[-1]))
                desc = None
            if desc is not None:
                findings += [dict(f) for f in desc.get('diagnostics', [])]
                wname = 'world[%s]' % desc['name']
                for m in desc['models']:
                    prefix = '%s/model[%s]/' % (wname, m['name'])
                    for l in m['links']:
                        inert = l['inertial']
                        if inert is None:
                            continue
                        code, why = _core.inertial_problem(inert['mass'], inert['inertia'])
                        if why and not m['static']:
                            findings.append(_finding('error', code, prefix + 'link[%s]/inertial' % l['name'], why))
                    if not m['static']:
                        for f in model_check.inertia_findings(m, inertia_tolerance):
                            f['element'] = prefix + f['element']
                            findings.append(f)
                # models with plug-ins, sensors or joints are robots (docs/COMPAT-sdf.md 16): every plug-in with
                # its resolved parameters, as check_model lists them
                for r in desc.get('robots', []):
                    prefix = '%s/model[%s]/' % (wname, r['name'])
                    findings += [dict(f, element=prefix + f['element']) for f in r['model']['diagnostics']]
                    if r['config'] is None:
                        findings.append(_finding('error', 'plugin-config', prefix, r['config_error']))
                        continue
                    findings += [dict(f, element=prefix + f['element']) for f in r['config']['diagnostics']]
                    plugins += [dict(p, model=r['name']) for p in r['config']['plugins']]
    order = {'error': 0, 'warning': 1, 'info': 2}
    findings.sort(key=lambda f: (order[f['severity']], f['element']))
    counts = {s: sum(1 for f in findings if f['severity'] == s) for s in ('error', 'warning', 'info')}
    return {'source': path, 'findings': findings, 'counts': counts, 'plugins': plugins}
