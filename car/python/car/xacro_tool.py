"""xacro expansion with the upstream ROS xacro library (PyPI ``xacro``, pinned in requirements.txt), in
Noetic's dialect (xacro 1.14; see car.xacro14 and docs/xacro14.md).

``$(find PKG)`` resolves through ROS_PACKAGE_PATH as in ROS; ``$(find car)`` also works outside a sourced
workspace. Errors become one ``ExpandError`` line: ``FILE[:LINE]: reason``.
"""
from __future__ import annotations

import os
import re
import sys
import xml.parsers.expat

from car.paths import package_dir

PACKAGE_ROOT = package_dir()


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


def _xacro():
    """The xacro module with Noetic's substitution args installed."""
    try:
        from car import xacro14
        return xacro14.install()
    except (ImportError, RuntimeError) as e:  # pragma: no cover - set-up problem
        raise ExpandError('xacro', None, 'the xacro library is not usable (%s); run tools/setup.sh' % e)


def expand(path: str, mappings: dict | None = None, verbosity: int = 1) -> str:
    """Expands a xacro (or plain URDF) file to URDF text. Raises ExpandError.

    verbosity as xacro's: 0 quiet (no warnings), 1 default (warnings with their location), 2 and more: more."""
    return expand_doc(path, mappings, verbosity)[0]


def dependencies(path: str, mappings: dict | None = None) -> list:
    """Files the expansion of path reads (includes and load_yaml files), in first-read order, as xacro --deps."""
    return expand_doc(path, mappings, 0)[1]


def expand_doc(path: str, mappings: dict | None = None, verbosity: int = 1):
    """(URDF text, files read) for a xacro (or plain URDF) file. Raises ExpandError."""
    _ensure_car_on_package_path()
    xacro = _xacro()
    if not os.path.isfile(path):
        raise ExpandError(path, None, 'no such file')
    # module-level state of xacro: files read by this expansion only
    xacro.all_includes = []
    try:
        doc = xacro.process_file(path, mappings=dict(mappings or {}), verbosity=verbosity)
    except xml.parsers.expat.ExpatError as e:
        # xacro's file stack ends with the file being parsed
        culprit = xacro.filestack[-1] if xacro.filestack and xacro.filestack[-1] else path
        raise ExpandError(culprit, e.lineno, 'malformed XML: %s' % xml.parsers.expat.ErrorString(e.code))
    except Exception as e:  # XacroException and the evaluation errors it wraps
        raise _explain(e, path, xacro) from None
    deps = list(dict.fromkeys(xacro.all_includes))
    return doc.toprettyxml(indent='  '), deps


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
        missing = m.group(1).strip("'\"")
        base = os.path.basename(missing)
        # xacro.load_yaml() reads files too; its failure is reported while evaluating the expression
        what = 'YAML file' if 'load_yaml(' in msg else 'included file'
        return ExpandError(culprit, _line_of(culprit, base), '%s not found: %s' % (what, missing))
    # xacro.fatal() and other evaluation errors: the line of the expression, where it is written once
    m = re.search(r"when evaluating expression '(.*?)'(?: when evaluating|$)", msg)
    if m:
        lines = _lines_of(culprit, '${%s}' % m.group(1))
        if len(lines) == 1:
            return ExpandError(culprit, lines[0], msg)
    return ExpandError(culprit, None, msg or repr(e))


def _lines_of(path: str | None, needle: str) -> list:
    """Every line of a file that contains needle."""
    if not path or not needle or not os.path.isfile(path):
        return []
    with open(path, encoding='utf-8', errors='replace') as f:
        return [n for n, text in enumerate(f, 1) if needle in text]


USAGE = """usage: xacro [options] FILE [name:=value ...]
Expands FILE with the upstream xacro library in Noetic's dialect (1.14); $(find PKG) and xacro args resolve
as in ROS.
  -o FILE          write the output to FILE instead of stdout
  --deps           print the files FILE includes or loads (space separated) instead of the XML
  -q               quiet: no warnings (verbosity 0)
  -v               more verbose (repeatable)
  --verbosity N    0 quiet, 1 default (warnings and their location), 2 and more: more
  --inorder, -i    accepted; in-order processing is the default
"""


def main(argv=None) -> int:
    """Command line as xacro 1.14's: xacro [options] FILE [name:=value ...]. Exit status 2 on error."""
    argv = list(sys.argv[1:] if argv is None else argv)
    mappings, rest = parse_mappings(argv)
    out = None
    deps = False
    verbosity = 1
    files = []
    i = 0
    while i < len(rest):
        a = rest[i]
        if a in ('-o', '--verbosity'):
            if i + 1 >= len(rest):
                print('xacro: error: %s needs a value' % a, file=sys.stderr)
                return 2
            if a == '-o':
                out = rest[i + 1]
            else:
                try:
                    verbosity = int(rest[i + 1])
                except ValueError:
                    print('xacro: error: --verbosity needs an integer (got %r)' % rest[i + 1], file=sys.stderr)
                    return 2
            i += 2
            continue
        if a in ('--inorder', '-i', '--xacro-ns'):
            pass
        elif a == '--deps':
            deps = True
        elif a == '-q':
            verbosity = 0
        elif a == '-v':
            verbosity += 1
        elif a in ('-h', '--help'):
            print(USAGE, end='')
            return 0
        elif a.startswith('-'):
            print('xacro: error: unknown option %s' % a, file=sys.stderr)
            return 2
        else:
            files.append(a)
        i += 1
    if len(files) != 1:
        print('xacro: error: expected exactly one input file (got %d)' % len(files), file=sys.stderr)
        return 2
    try:
        text, read = expand_doc(files[0], mappings, verbosity)
    except ExpandError as e:
        print('xacro: error: %s' % e, file=sys.stderr)
        return 2
    if deps:
        text = ' '.join(read) + '\n'
    if out:
        with open(out, 'w', encoding='utf-8') as f:
            f.write(text)
    else:
        sys.stdout.write(text)
    return 0
