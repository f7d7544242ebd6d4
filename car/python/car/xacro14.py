"""Noetic's xacro (1.14 dialect) on the PyPI xacro 2.1.1 (pinned in requirements.txt).

PyPI xacro 2.1.1 is the ros/xacro ``ros2`` line: the same macro language as noetic-devel (1.14.17 plus the
YAML unit tags), but its ``$(...)`` substitution args come from its own copy whose ``$(find)`` needs ament.
Noetic's xacro resolves them with roslaunch instead. ``install()`` puts that back: it replaces the module-level
``xacro.eval_extension`` (called by ``eval_text`` for every ``$(...)``) with 1.14's behaviour on Debian's
roslaunch, and the ament ``find`` of 2.1.1's own ``$(eval)`` table with rospkg. Nothing else is changed. Without
roslaunch and rospkg (a pip install, no ROS) 2.1.1's own substitution args run, their $(find) resolving car itself
and ROS_PACKAGE_PATH's packages.
See docs/xacro14.md for the rules.
"""
from __future__ import annotations

import os

# the PyPI release this layer was written against (requirements.txt)
PINNED = '2.1.1'

_installed = False


class PackageNotFound(LookupError):
    """$(find PKG) without rospkg (a pip install): PKG is not car and in no ROS_PACKAGE_PATH entry."""


def _find_package(pkg: str) -> str:
    """catkin's $(find PKG): the package directory found through ROS_PACKAGE_PATH. Without rospkg (a pip install,
    no ROS): car's own folder for car, else a ROS_PACKAGE_PATH entry that is PKG or holds it as ENTRY/PKG."""
    try:
        import rospkg
    except ImportError:
        from car.paths import package_dir
        if pkg == 'car':
            return package_dir()
        for entry in filter(None, os.environ.get('ROS_PACKAGE_PATH', '').split(os.pathsep)):
            for cand in (entry, os.path.join(entry, pkg)):
                if _package_xml_name(cand) == pkg:
                    return cand
        raise PackageNotFound(pkg)
    return rospkg.RosPack().get_path(pkg)


def _package_xml_name(folder: str) -> str | None:
    """<name> of FOLDER/package.xml, or None."""
    import xml.etree.ElementTree as ET
    try:
        return (ET.parse(os.path.join(folder, 'package.xml')).getroot().findtext('name') or '').strip()
    except (OSError, ET.ParseError):
        return None


def _eval_extension(s: str):
    """xacro 1.14's eval_extension: $(cwd), then roslaunch's substitution args (anon left as written)."""
    import xacro
    if s == '$(cwd)':
        return os.path.abspath(xacro.root_dir)
    try:
        from roslaunch import substitution_args
        from rospkg.common import ResourceNotFound
    except ImportError:
        return _eval_extension_without_ros(s)
    try:
        return substitution_args.resolve_args(s, context=xacro.substitution_args_context, resolve_anon=False)
    except substitution_args.ArgException as e:
        raise xacro.XacroException('Undefined substitution argument', exc=e)
    except ResourceNotFound as e:
        raise xacro.XacroException('resource not found:', exc=e)


def _eval_extension_without_ros(s: str):
    """Where roslaunch is missing (a pip install, no ROS): xacro 2.1.1's own substitution args, which have the same
    $(arg), $(env), $(optenv), $(dirname) and $(eval), and $(find) through _find_package; no $(anon)."""
    import xacro
    import xacro.substitution_args as sa
    try:
        return sa.resolve_args(s, context=xacro.substitution_args_context)
    except sa.ArgException as e:
        raise xacro.XacroException('Undefined substitution argument', exc=e)
    except PackageNotFound as e:
        raise xacro.XacroException('resource not found:', exc=e)
    except sa.SubstitutionException as e:
        raise xacro.XacroException('substitution args (without ROS):', exc=e)


def installed_version() -> str | None:
    """Version of the installed xacro distribution, or None."""
    try:
        from importlib.metadata import version
        return version('xacro')
    except Exception:  # pragma: no cover - not installed
        return None


def install():
    """Makes the imported xacro module behave as Noetic's xacro 1.14. Idempotent; returns the module.

    Raises RuntimeError when the installed xacro lacks the hooks this layer replaces (another version)."""
    global _installed
    import xacro
    if _installed:
        return xacro
    import xacro.substitution_args as sa
    missing = [n for n in ('eval_extension', 'substitution_args_context', 'root_dir', 'XacroException',
                           'YamlDictWrapper', 'process_file') if not hasattr(xacro, n)]
    missing += ['substitution_args.' + n for n in ('_eval_find', '_eval_dict') if not hasattr(sa, n)]
    if missing:
        raise RuntimeError('xacro %s lacks %s: car needs xacro==%s (requirements.txt); run tools/setup.sh'
                           % (installed_version(), ', '.join(missing), PINNED))
    xacro.eval_extension = _eval_extension
    sa._eval_find = _find_package
    sa._eval_dict['find'] = _find_package
    _installed = True
    return xacro
