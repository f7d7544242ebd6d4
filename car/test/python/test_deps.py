"""Declared dependencies (tools/check_deps.py): the repository declares all it uses, and a gap is caught."""
import os
import subprocess
import sys

from conftest import REPO

CHECK = os.path.join(REPO, 'tools', 'check_deps.py')


def run_check(root):
    return subprocess.run([sys.executable, CHECK, '--root', str(root)], capture_output=True, text=True, timeout=120)


def test_repository_declares_every_dependency_it_uses():
    r = run_check(REPO)
    assert r.returncode == 0, r.stdout
    assert r.stdout.strip().endswith('0 undeclared dependencies')


def make_package(tmp_path, code, depends=(), debs=()):
    (tmp_path / 'tools').mkdir()
    (tmp_path / 'tools' / 'setup.sh').write_text('DEB_PACKAGES=(\n  %s\n)\n' % ' '.join(debs))
    (tmp_path / 'package.xml').write_text(
        '<package format="3"><name>pkg</name>%s</package>' % ''.join('<depend>%s</depend>' % d for d in depends))
    (tmp_path / 'python').mkdir()
    (tmp_path / 'python' / 'node.py').write_text(code)


def test_an_import_neither_declared_nor_installed_is_named_with_file_line_and_both_places(tmp_path):
    make_package(tmp_path, 'import os\nfrom visualization_msgs.msg import MarkerArray\n')
    r = run_check(tmp_path)
    assert r.returncode == 1
    lines = r.stdout.splitlines()
    assert 'python/node.py: line 2 imports visualization_msgs needs <depend>visualization_msgs</depend> ' \
           '(or build/exec/test) in package.xml' in lines
    assert 'python/node.py: line 2 imports visualization_msgs needs Debian package python3-visualization-msgs, ' \
           'which tools/setup.sh does not install' in lines
    assert lines[-1] == 'check_deps: 2 undeclared dependencies'


def test_an_import_declared_and_installed_passes(tmp_path):
    make_package(tmp_path, 'from visualization_msgs.msg import MarkerArray\n', depends=['visualization_msgs'],
                 debs=['python3-visualization-msgs'])
    assert run_check(tmp_path).returncode == 0


def test_a_module_in_no_table_is_a_gap(tmp_path):
    make_package(tmp_path, 'import frobnicate\n')
    r = run_check(tmp_path)
    assert r.returncode == 1
    assert 'python/node.py: line 1 imports frobnicate, which is in no table of tools/check_deps.py; add it' in r.stdout


def test_a_header_of_an_undeclared_library_is_a_gap(tmp_path):
    make_package(tmp_path, '')
    (tmp_path / 'src').mkdir()
    (tmp_path / 'src' / 'a.cpp').write_text('#include <vector>\n#include <embree3/rtcore.h>\n')
    r = run_check(tmp_path)
    assert 'src/a.cpp: line 2 includes <embree3/rtcore.h> needs <depend>libembree-dev</depend>' in r.stdout
    assert 'needs Debian package libembree-dev, which tools/setup.sh does not install' in r.stdout
