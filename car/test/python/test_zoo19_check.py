"""check_model on what trying real robots brought up (issue 19 item 7): a description package nested in a catkin
workspace (package:// through rospack's crawl) and model-level <gazebo> elements. Fixtures: test/data/zoo19/."""
import os
import subprocess
import sys

from conftest import DATA, ROOT

ZOO19 = os.path.join(DATA, 'zoo19')
NESTED = os.path.join(ZOO19, 'nested_mesh_bot.urdf')


def check_args(args, package_path):
    """check_model ARGS in a process whose ROS_PACKAGE_PATH is package_path (the crawl is cached per process)."""
    env = dict(os.environ, ROS_PACKAGE_PATH=package_path)
    return subprocess.run([sys.executable, os.path.join(ROOT, 'scripts', 'check_model')] + args,
                          capture_output=True, text=True, timeout=120, env=env)


def check(path, package_path):
    return check_args([path], package_path)


def test_nested_package_mesh_resolves_from_the_workspace_src():
    # ws/src/zoo19_repo/description holds package zoo19_arm_description: found from ws/src as rospack finds it
    p = check(NESTED, os.path.join(ZOO19, 'ws', 'src'))
    assert p.returncode == 0, p.stdout + p.stderr
    assert 'mesh-unresolved' not in p.stdout and 'not found' not in p.stdout


def test_nested_package_mesh_outside_the_path_is_an_error_naming_the_uri():
    p = check(NESTED, os.path.join(ZOO19, 'ws2'))
    assert p.returncode == 2, p.stdout + p.stderr
    assert "link[base_link]/collision[0]/mesh: mesh 'package://zoo19_arm_description/meshes/cube.obj' not found" \
        in ' '.join(p.stdout.split())


def test_model_level_static_is_a_warning_in_the_report(tmp_path):
    xml = open(NESTED).read().replace('</robot>', '<gazebo><static>true</static></gazebo></robot>')
    f = tmp_path / 'static_bot.urdf'
    f.write_text(xml)
    p = check(str(f), os.path.join(ZOO19, 'ws', 'src'))
    assert p.returncode == 0, p.stdout + p.stderr
    line = [l for l in p.stdout.splitlines() if 'gazebo/static' in l]
    assert len(line) == 1 and line[0].split()[0] == 'warning', p.stdout
    # strict mode fails on it
    strict = check_args(['--strict', str(f)], os.path.join(ZOO19, 'ws', 'src'))
    assert strict.returncode == 1, strict.stdout
