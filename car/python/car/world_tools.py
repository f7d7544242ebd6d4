"""SDF world tools: flatten a world and check it.

Every rule lives in the core (car._core): the include rule (car_sim::resolve_uri, model.config, at most 32 includes
deep), nested models hoisted as 'parent::child', <state> applied (car_sim::flatten_world_file, which the simulator's
loader shares), and the check's rules on poses and geometry (car_sim::check_world_file, validate.cpp;
docs/COMPAT-validation.md "world_tool check"). This module writes the flattened text out and adds to a check what
the model check adds to a URDF's (inertia against the shapes, the plug-ins' parameters).
Include rule:
  model://NAME[/rest]  -> the first folder NAME in GAZEBO_MODEL_PATH (':'-separated, in order), then car's models/
  package://PKG/rest   -> PKG's folder found through ROS_PACKAGE_PATH
  file://PATH, PATH    -> absolute, or relative to the including file's folder
A folder is a model folder: its model.config names the SDF file (the highest <sdf version> up to 1.9).
"""
from __future__ import annotations

import xml.etree.ElementTree as ET


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


# ---- flatten ------------------------------------------------------------------------------------------

def flatten(path: str, warnings: list | None = None) -> ET.ElementTree:
    """One self-contained world: includes resolved and replaced, nested models hoisted, <state> applied (the core's
    car_sim::flatten_world_file, which reads the file: its verdicts on malformed XML and DTD entities are the tool's).
    With a list for warnings, an include that resolves nowhere is left out, as the simulator leaves it out, and its
    finding appended there; without, it is an error."""
    from car import _core
    try:
        # bytes in the input's encoding, which its declaration names
        data = _core.flatten_world(path, warnings)
    except _core.LoadError as e:
        raise WorldError(e.file, e.element, e.reason)
    parser = ET.XMLParser(target=ET.TreeBuilder())
    try:
        # what tinyxml2 passes and expat does not (bytes that are not text in the declared encoding)
        parser.feed(data)
        tree = ET.ElementTree(parser.close())
    except ET.ParseError as e:
        raise WorldError(path, '', 'malformed XML: %s' % e)
    ET.indent(tree, space='  ')
    return tree


def flatten_to_string(path: str, warnings: list | None = None) -> str:
    return "<?xml version='1.0'?>\n" + ET.tostring(flatten(path, warnings).getroot(), encoding='unicode') + '\n'


def load(path: str, warnings: list | None = None) -> dict:
    """The world as world_tool map and plot read it, in one core call (car._core.load_flattened_world): flattened as
    flatten() flattens it (warnings the same), its text read in UTF-8, then loaded as the simulator loads SDF text;
    the dict car._core.load_world_file gives. Raises WorldError."""
    from car import _core
    try:
        return _core.load_flattened_world(path, warnings)
    except _core.LoadError as e:
        raise WorldError(e.file, e.element, e.reason)


# ---- check --------------------------------------------------------------------------------------------

def check(path: str, inertia_tolerance: float = 0.10) -> dict:
    """The world read by the core in one call (car._core.check_world: flattened, held to the check's rules, loaded
    as the simulator loads it), plus the model check's inertia against the shapes for every dynamic link and the
    plug-ins of world models simulated as robots. A report like check_model's: {'source', 'findings', 'counts',
    'plugins'}."""
    from car import _core, model_check
    result = _core.check_world(path)
    findings = [dict(f) for f in result['findings']]
    plugins = []  # the plug-ins of world models simulated as robots
    desc = result['world']
    if desc is not None:
        wname = 'world[%s]' % desc['name']
        for m in desc['models']:
            if m['static']:
                continue
            for f in model_check.inertia_findings(m, inertia_tolerance):
                f['element'] = '%s/model[%s]/%s' % (wname, m['name'], f['element'])
                findings.append(f)
        # models with plug-ins, sensors or joints are robots (docs/COMPAT-sdf.md 16): every plug-in with its
        # resolved parameters, as check_model lists them
        for r in desc.get('robots', []):
            prefix = '%s/model[%s]/' % (wname, r['name'])
            findings += [dict(f, element=prefix + f['element']) for f in r['model']['diagnostics']]
            if r['config'] is None:
                findings.append({'severity': 'error', 'code': 'plugin-config', 'element': prefix,
                                 'message': r['config_error'], 'line': 0})
                continue
            findings += [dict(f, element=prefix + f['element']) for f in r['config']['diagnostics']]
            plugins += [dict(p, model=r['name']) for p in r['config']['plugins']]
    order = {'error': 0, 'warning': 1, 'info': 2}
    findings.sort(key=lambda f: (order[f['severity']], f['element']))
    counts = {s: sum(1 for f in findings if f['severity'] == s) for s in ('error', 'warning', 'info')}
    return {'source': path, 'findings': findings, 'counts': counts, 'plugins': plugins}
