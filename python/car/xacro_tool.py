"""xacro expansion with the upstream ROS xacro library (PyPI ``xacro``, pinned in requirements.txt).

``$(find PKG)`` resolves through ROS_PACKAGE_PATH as in ROS; ``$(find car)`` also works outside a sourced
workspace. Errors become one ``ExpandError`` line: ``FILE[:LINE]: reason``.
"""
from __future__ import annotations

import os
import re
import sys
import xml.parsers.expat

PACKAGE_ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


class ExpandError(Exception):
    """A xacro document could not be expanded. str() is one line: FILE[:LINE]: reason."""

    def __init__(self, file: str, line: int | None, reason: str):
        self.file, self.line, self.reason = file, line, reason
        where = file if not line else '%s:%d' % (file, line)
        super().__init__('%s: %s' % (where, reason))


def _ensure_car_on_package_path() -> None:
    """Lets $(find car) work when no workspace is sourced (tests, a plain shell)."""
    paths = [p for p in os.environ.get('ROS_PACKAGE_PATH', '').split(os.pathsep) if p]
    if os.path.isfile(os.path.join(PACKAGE_ROOT, 'package.xml')) and PACKAGE_ROOT not in paths:
        try:
            import rospkg
            rospkg.RosPack().get_path('car')
            return
        except Exception:
            os.environ['ROS_PACKAGE_PATH'] = os.pathsep.join(paths + [PACKAGE_ROOT])


def _line_of(path: str | None, needle: str) -> int | None:
    """First line of a file that contains needle, to point at the culprit."""
    if not path or not needle or not os.path.isfile(path):
        return None
    with open(path, encoding='utf-8', errors='replace') as f:
        for n, text in enumerate(f, 1):
            if needle in text:
                return n
    return None


def parse_mappings(args):
    """Splits 'name:=value' arguments from the rest, as roslaunch and xacro do."""
    mappings, rest = {}, []
    for a in args:
        if ':=' in a:
            k, v = a.split(':=', 1)
            mappings[k] = v
        else:
            rest.append(a)
    return mappings, rest


def expand(path: str, mappings: dict | None = None) -> str:
    """Expands a xacro (or plain URDF) file to URDF text. Raises ExpandError."""
    _ensure_car_on_package_path()
    try:
        import xacro
    except ImportError as e:  # pragma: no cover - set-up problem
        raise ExpandError(path, None, 'the xacro library is not installed (%s); run tools/setup.sh' % e)
    if not os.path.isfile(path):
        raise ExpandError(path, None, 'no such file')
    try:
        doc = xacro.process_file(path, mappings=dict(mappings or {}), in_order=True)
    except xml.parsers.expat.ExpatError as e:
        # xacro's file stack ends with the file being parsed
        culprit = xacro.filestack[-1] if xacro.filestack and xacro.filestack[-1] else path
        raise ExpandError(culprit, e.lineno, 'malformed XML: %s' % xml.parsers.expat.ErrorString(e.code))
    except Exception as e:  # XacroException and the evaluation errors it wraps
        raise _explain(e, path, xacro) from None
    return doc.toprettyxml(indent='  ')


def _explain(e: Exception, path: str, xacro_mod) -> ExpandError:
    msg = ' '.join(str(e).split())
    stack = [f for f in (xacro_mod.filestack or []) if f]
    culprit = stack[-1] if stack else path
    m = re.search(r"name '([^']+)' is not defined", msg)
    if m:
        name = m.group(1)
        for f in reversed(stack or [path]):
            line = _line_of(f, name)
            if line:
                return ExpandError(f, line, "undefined property or name '%s' (%s)" % (name, msg))
        return ExpandError(culprit, None, "undefined property or name '%s'" % name)
    m = re.search(r'unknown macro name:?\s*(\S+)', msg)
    if m:
        name = m.group(1)
        short = name.split(':', 1)[-1]
        return ExpandError(culprit, _line_of(culprit, short), "undefined macro '%s'" % short)
    m = re.search(r'No such file or directory: (\S+)', msg)
    if m:
        missing = m.group(1)
        base = os.path.basename(missing)
        return ExpandError(culprit, _line_of(culprit, base), 'included file not found: %s' % missing)
    return ExpandError(culprit, None, msg or repr(e))


def main(argv=None) -> int:
    """Command line: xacro FILE [-o OUT] [name:=value ...]. Old flags (--inorder, -i) are accepted."""
    argv = list(sys.argv[1:] if argv is None else argv)
    mappings, rest = parse_mappings(argv)
    out = None
    files = []
    i = 0
    while i < len(rest):
        a = rest[i]
        if a == '-o':
            if i + 1 >= len(rest):
                print('xacro: error: -o needs a file name', file=sys.stderr)
                return 2
            out = rest[i + 1]
            i += 2
            continue
        if a in ('--inorder', '-i', '--xacro-ns'):
            i += 1
            continue
        if a in ('-h', '--help'):
            print('usage: xacro FILE [-o OUT] [name:=value ...]\n'
                  'Expands FILE with the upstream xacro library; $(find PKG) and xacro args resolve as in ROS.')
            return 0
        if a.startswith('-'):
            print('xacro: error: unknown option %s' % a, file=sys.stderr)
            return 2
        files.append(a)
        i += 1
    if len(files) != 1:
        print('xacro: error: expected exactly one input file (got %d)' % len(files), file=sys.stderr)
        return 2
    try:
        text = expand(files[0], mappings)
    except ExpandError as e:
        print('xacro: error: %s' % e, file=sys.stderr)
        return 2
    if out:
        with open(out, 'w', encoding='utf-8') as f:
            f.write(text)
    else:
        sys.stdout.write(text)
    return 0
