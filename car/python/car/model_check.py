"""Physics-aware model check: what urdfdom's check_urdf says, plus what a simulator needs to hear.

The model is read by the simulator's own core (car._core), so the check and the simulator agree on what a
file means. Exit status: 0 clean, 2 on errors, 1 on warnings with --strict.
"""
from __future__ import annotations

import argparse
import json
import os
import sys

import numpy as np

from car import inertia as inertia_mod
from car import xacro_tool

SEVERITY_ORDER = {'error': 0, 'warning': 1, 'info': 2}
DEFAULT_INERTIA_TOLERANCE = 0.10


class CheckInputError(Exception):
    """The input could not be read at all (missing file, malformed XML, xacro failure)."""


def _core():
    from car import _core  # built by catkin into the devel space
    return _core


def load_text(path: str, mappings: dict | None = None) -> str:
    """URDF text of a .urdf file, or of a .xacro file expanded by the xacro tool."""
    if path.endswith('.xacro') or mappings:
        try:
            return xacro_tool.expand(path, mappings)
        except xacro_tool.ExpandError as e:
            raise CheckInputError(str(e))
    try:
        with open(path, encoding='utf-8') as f:
            return f.read()
    except OSError as e:
        raise CheckInputError('%s: %s' % (path, e.strerror.lower() if e.strerror else e))
    except UnicodeDecodeError as e:
        raise CheckInputError('%s: not UTF-8 text (byte 0x%02x at offset %d)' % (path, e.object[e.start], e.start))


def _fmt_tensor(m) -> list:
    """Six significant digits; round-off below 1e-9 of the largest entry shows as 0."""
    a = np.asarray(m, dtype=float)
    tiny = 1e-9 * max(float(np.abs(a).max()), 1e-300)
    return [[0.0 if abs(v) < tiny else float('%.6g' % v) for v in row] for row in a]


def inertia_findings(model: dict, tolerance: float) -> list:
    """Compares each link's declared inertia with the one its mass and collision shapes imply."""
    out = []
    for link in model['links']:
        inertial = link['inertial']
        if not inertial or inertial['mass'] <= 0 or not link['collisions']:
            continue
        exp = inertia_mod.expected_inertia(inertial['mass'], link['collisions'], inertial['origin']['rotation'])
        if exp is None:
            continue
        expected, _centroid = exp
        declared = np.array(inertial['inertia'])
        with np.errstate(invalid='ignore', over='ignore'):
            err = inertia_mod.relative_error(declared, expected)
        # a mass such as 1e300 kg overflows the comparison (nan): the mass-range finding names the number instead
        if not np.isfinite(err) or err <= tolerance:
            continue
        shapes = ', '.join(_describe_shape(s) for s in link['collisions'])
        out.append({
            'severity': 'warning', 'code': 'inertia-mismatch',
            'element': 'link[%s]/inertial/inertia' % link['name'], 'line': 0,
            'message': 'declared inertia is %.0f%% off the tensor of a uniform %g kg %s' % (
                100 * err, inertial['mass'], shapes),
            'declared': _fmt_tensor(declared), 'expected': _fmt_tensor(expected),
        })
    return out


def _describe_shape(s: dict) -> str:
    if s['type'] == 'box':
        return 'box %g x %g x %g m' % tuple(s['size'])
    if s['type'] == 'cylinder':
        return 'cylinder r %g m, length %g m' % (s['radius'], s['length'])
    if s['type'] == 'sphere':
        return 'sphere r %g m' % s['radius']
    return s['type']


def mesh_findings(model: dict, base_dir: str) -> list:
    """An error for each collision mesh URI that does not resolve (the simulator refuses such a robot). A visual's
    is the core's warning (inspect_urdf_string's mesh_warnings): Gazebo simulates such a robot."""
    core = _core()
    out = []
    for link in model['links']:
        for kind in ('collisions',):
            for i, s in enumerate(link[kind]):
                shape = s.get('shape', s)
                if shape.get('type') != 'mesh' or core.resolve_uri(shape['uri'], base_dir):
                    continue
                out.append({
                    'severity': 'error', 'code': 'mesh-unresolved',
                    'element': 'link[%s]/%s[%d]/mesh' % (link['name'], kind[:-1], i), 'line': 0,
                    'message': "mesh '%s' not found (relative to '%s'; package:// through ROS_PACKAGE_PATH, "
                               "model:// through GAZEBO_MODEL_PATH)" % (shape['uri'], base_dir or '.'),
                })
    return out


def check_text(xml: str, source: str, tolerance: float = DEFAULT_INERTIA_TOLERANCE) -> dict:
    """Runs every check on URDF text. Raises CheckInputError when the XML cannot be read.

    Findings include what the import does as Gazebo does it (docs/COMPAT-spawn.md): each lumped link (note),
    each dropped link (warning), the `world` anchor (note); values that cannot be read carry their line.
    """
    core = _core()
    try:
        r = core.inspect_urdf_string(xml, source)
        # inertia is compared link by link as written, before lumping merges links
        as_written = core.inspect_urdf_string(xml, source, lump_fixed_joints=False)['model']
    except core.LoadError as e:
        raise CheckInputError(str(e))
    model = r['model']
    findings = list(model['diagnostics'])
    if r['config'] is not None:
        findings += r['config']['diagnostics']
    if r['config_error'] is not None:
        findings.append(r['config_error'])
    findings += inertia_findings(as_written, tolerance)
    base_dir = os.path.dirname(os.path.abspath(source)) if source and not source.startswith('<') else ''
    unresolved = mesh_findings(model, base_dir)
    findings += unresolved
    # a mesh that resolves but cannot be read is the spawn's load error
    if not unresolved and r.get('mesh_error') is not None:
        findings.append(r['mesh_error'])
    findings += r.get('mesh_warnings') or []
    findings.sort(key=lambda f: (SEVERITY_ORDER[f['severity']], f['element']))
    counts = {s: sum(1 for f in findings if f['severity'] == s) for s in ('error', 'warning', 'info')}
    return {
        'source': source,
        'robot': model['name'],
        'links': [_link_summary(l) for l in model['links']],
        'joints': [{k: j[k] for k in ('name', 'type', 'parent', 'child', 'axis')} for j in model['joints']],
        'plugins': r['config']['plugins'] if r['config'] else [],
        'lumped': [{k: l[k] for k in ('name', 'parent', 'joint')} for l in model['lumped']],
        'dropped': [{k: l[k] for k in ('name', 'joint', 'subtree')} for l in model['dropped']],
        'world_joints': list(model['world_joints']),
        'findings': findings,
        'counts': counts,
    }


def _link_summary(link: dict) -> dict:
    return {
        'name': link['name'],
        'mass': link['inertial']['mass'] if link['inertial'] else None,
        'collisions': [_describe_shape(s) for s in link['collisions']],
        'gazebo_material': link['gazebo']['material'],
    }


def exit_code(report: dict, strict: bool) -> int:
    if report['counts']['error']:
        return 2
    if strict and report['counts']['warning']:
        return 1
    return 0


def format_report(report: dict) -> str:
    lines = []
    links, joints = report['links'], report['joints']
    mass = sum(l['mass'] or 0.0 for l in links)
    lines.append("car model check: %s (robot '%s')" % (report['source'], report['robot']))
    kinds = {}
    for j in joints:
        kinds[j['type']] = kinds.get(j['type'], 0) + 1
    lines.append('  %d links, %d joints (%s), total mass %.4g kg' % (
        len(links), len(joints), ', '.join('%d %s' % (n, k) for k, n in sorted(kinds.items())), mass))
    lines.append('  links:')
    for l in links:
        lines.append('    %-16s %10s  %s%s' % (
            l['name'], '-' if l['mass'] is None else '%.4g kg' % l['mass'],
            '; '.join(l['collisions']) or 'no collision',
            ('  [%s]' % l['gazebo_material']) if l['gazebo_material'] else ''))
    if report.get('world_joints'):
        lines.append('  anchored to the world by: %s' % ', '.join(report['world_joints']))
    if report.get('lumped'):
        lines.append('  lumped (fixed joints, as Gazebo): %s' % ', '.join(
            '%s -> %s' % (l['name'], l['parent']) for l in report['lumped']))
    if report.get('dropped'):
        lines.append('  dropped (no mass on a moving joint, as Gazebo): %s' % ', '.join(
            l['name'] + (' (with %s)' % ', '.join(l['subtree']) if l['subtree'] else '') for l in report['dropped']))
    lines.append('  plug-ins:')
    if not report['plugins']:
        lines.append('    (none simulated)')
    for p in report['plugins']:
        head = '    %s (%s) -> %s' % (p['name'], p['filename'], p['kind'])
        if p['sensor']:
            head += " in sensor '%s' (%s) on link '%s'" % (p['sensor'], p['sensor_type'], p['link'])
        lines.append(head)
        for prm in p['params']:
            unit = (' ' + prm['unit']) if prm['unit'] else ''
            lines.append('      %-32s %s%s%s' % (prm['key'], prm['value'] if prm['value'] != '' else "''", unit,
                                                '   (default)' if prm['default'] else ''))
    lines.append('  findings:')
    if not report['findings']:
        lines.append('    none')
    for f in report['findings']:
        where = f['element'] + ((' (line %d)' % f['line']) if f.get('line') else '')
        lines.append('    %-7s %s: %s' % (f['severity'], where, f['message']))
        if 'expected' in f:
            lines.append('            declared %s' % _rows(f['declared']))
            lines.append('            expected %s' % _rows(f['expected']))
    c = report['counts']
    lines.append('summary: %d error(s), %d warning(s), %d note(s)' % (c['error'], c['warning'], c['info']))
    return '\n'.join(lines)


def _rows(m) -> str:
    return '[' + '; '.join(' '.join('%.6g' % v for v in row) for row in m) + '] kg m^2'


def main(argv=None) -> int:
    argv = list(sys.argv[1:] if argv is None else argv)
    mappings, rest = xacro_tool.parse_mappings(argv)
    ap = argparse.ArgumentParser(
        prog='check_model',
        description='Check a URDF or xacro model the way car will simulate it. Extra name:=value arguments '
                    'are xacro args. Exit 0 clean, 2 on errors, 1 on warnings with --strict.')
    ap.add_argument('file')
    ap.add_argument('--json', action='store_true', help='print the report as JSON')
    ap.add_argument('--strict', action='store_true', help='warnings fail the check (exit 1)')
    ap.add_argument('--inertia-tolerance', type=float, default=DEFAULT_INERTIA_TOLERANCE,
                    help='relative difference tolerated between declared and shape inertia (default 0.10)')
    args = ap.parse_args(rest)
    try:
        report = check_text(load_text(args.file, mappings), args.file, args.inertia_tolerance)
    except CheckInputError as e:
        if args.json:
            print(json.dumps({'source': args.file, 'error': str(e), 'exit_code': 2}, indent=2))
        else:
            print('check_model: error: %s' % e, file=sys.stderr)
        return 2
    code = exit_code(report, args.strict)
    if args.json:
        report['exit_code'] = code
        print(json.dumps(report, indent=2))
    else:
        print(format_report(report))
    return code
