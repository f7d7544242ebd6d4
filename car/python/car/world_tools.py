"""SDF world tools: flatten a world, check it, slice it into a map.

The rules live in the core (car._core): the include rule (car_sim::resolve_uri, model.config, at most 32 includes
deep), nested models hoisted as 'parent::child', <state> applied (car_sim::flatten_world_file, which the simulator's
loader shares). This module reads the world as written, writes the flattened text, and checks what the XML shows.
Include rule:
  model://NAME[/rest]  -> the first folder NAME in GAZEBO_MODEL_PATH (':'-separated, in order), then car's models/
  package://PKG/rest   -> PKG's folder found through ROS_PACKAGE_PATH
  file://PATH, PATH    -> absolute, or relative to the including file's folder
A folder is a model folder: its model.config names the SDF file (the highest <sdf version> up to 1.9).
"""
from __future__ import annotations

import math
import xml.etree.ElementTree as ET

KNOWN_GEOMETRY = {'box', 'cylinder', 'sphere', 'plane', 'mesh', 'capsule', 'ellipsoid', 'heightmap', 'image',
                  'polyline', 'empty'}


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


# ---- poses --------------------------------------------------------------------------------------------

def check_pose(text: str | None, file: str, element: str) -> None:
    """Raises WorldError unless the text is 'x y z roll pitch yaw', 6 finite numbers, or empty."""
    vals = (text or '').split()
    if not vals:
        return
    try:
        nums = [float(v) for v in vals]
    except ValueError:
        nums = []
    if len(nums) != 6:
        raise WorldError(file, element, "pose '%s' is not 6 numbers (x y z roll pitch yaw)" % (text or '').strip())
    if not all(math.isfinite(v) for v in nums):
        raise WorldError(file, element, "pose '%s' has a non-finite value" % text.strip())


# ---- flatten ------------------------------------------------------------------------------------------

def parse_file(path: str) -> ET.ElementTree:
    """ET.parse, but the file is fed to expat in one piece: ET.parse feeds 64 kB at a time, and expat (2.5)
    rescans a token that spans the pieces from its start each time, so a 50 MB comment took minutes (quadratic)
    instead of a fraction of a second."""
    with open(path, 'rb') as f:
        data = f.read()
    parser = ET.XMLParser(target=ET.TreeBuilder())
    parser.feed(data)
    return ET.ElementTree(parser.close())


def flatten(path: str, warnings: list | None = None) -> ET.ElementTree:
    """One self-contained world: includes resolved and replaced, nested models hoisted, <state> applied (the core's
    car_sim::flatten_world_file). With a list for warnings, an include that resolves nowhere is left out, as the
    simulator leaves it out, and its finding appended there; without, it is an error."""
    from car import _core
    # expat reads the file as written first: its verdicts (malformed XML, entity expansion) are the tools' messages
    try:
        parse_file(path)
    except FileNotFoundError:
        raise WorldError(path, '', 'no such file')
    except ET.ParseError as e:
        raise WorldError(path, '', 'malformed XML: %s' % e)
    try:
        # bytes in the input's encoding, which its declaration names
        data = _core.flatten_world(path, warnings)
    except _core.LoadError as e:
        raise WorldError(e.file, e.element, e.reason)
    parser = ET.XMLParser(target=ET.TreeBuilder())
    parser.feed(data)
    tree = ET.ElementTree(parser.close())
    ET.indent(tree, space='  ')
    return tree


def flatten_to_string(path: str, warnings: list | None = None) -> str:
    return "<?xml version='1.0'?>\n" + ET.tostring(flatten(path, warnings).getroot(), encoding='unicode') + '\n'


# ---- check --------------------------------------------------------------------------------------------

def _finding(severity, code, element, message):
    return {'severity': severity, 'code': code, 'element': element, 'message': message, 'line': 0}


def _xml_findings(world: ET.Element, file: str) -> list:
    """What can be seen in the flattened XML: poses that do not parse, unknown or unsimulated geometry, meshes
    without a uri."""
    from car import _core
    out = []
    simulated = set(_core.simulated_geometry())  # the core's rule (docs/COMPAT-sdf.md rule 9)
    where_world = 'world[%s]' % world.get('name')

    def walk(e, path):
        for i, c in enumerate(e):
            name = c.get('name')
            here = '%s/%s' % (path, '%s[%s]' % (c.tag, name) if name else c.tag)
            if c.tag == 'pose':
                try:
                    check_pose(c.text, file, here)
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
                    elif g.tag not in simulated:
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
        left_out = []
        tree = flatten(path, left_out)
        findings += [dict(f) for f in left_out]
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
