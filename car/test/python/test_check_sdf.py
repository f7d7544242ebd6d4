"""check_model on an SDF model file and world_tool check on a world whose models carry plug-ins (issue 11 item 6;
docs/COMPAT-sdf.md)."""
import os

from car import model_check, world_tools
from conftest import DATA

SDF = os.path.join(DATA, 'sdf')


def _params(plugin):
    return {p['key']: p['value'] for p in plugin['params']}


def test_check_model_reads_an_sdf_model():
    path = os.path.join(SDF, 'diff_bot.sdf')
    report = model_check.check_text(model_check.load_text(path), path)
    assert report['robot'] == 'diff_bot'
    # four links, masses as written: 2 + 0.05 + 0.2 + 0.2 kg
    assert sorted(l['name'] for l in report['links']) == ['base_link', 'caster_link', 'left_wheel', 'right_wheel']
    assert sum(l['mass'] for l in report['links']) == 2.45
    # a revolute joint without <limit> is continuous; SDF keeps the fixed caster joint
    types = {j['name']: j['type'] for j in report['joints']}
    assert types == {'caster_joint': 'fixed', 'left_wheel_joint': 'continuous', 'right_wheel_joint': 'continuous'}
    kinds = {p['kind']: p for p in report['plugins']}
    assert set(kinds) == {'diff_drive', 'laser'}
    assert _params(kinds['diff_drive'])['wheelSeparation'] == '0.24'
    assert kinds['laser']['sensor'] == 'lidar' and kinds['laser']['link'] == 'base_link'


def test_check_model_report_lists_sdf_plugins():
    path = os.path.join(SDF, 'diff_bot.sdf')
    text = model_check.format_report(model_check.check_text(model_check.load_text(path), path))
    assert 'drive (libgazebo_ros_diff_drive.so) -> diff_drive' in text
    assert "lidar_plugin (libgazebo_ros_laser.so) -> laser in sensor 'lidar' (ray) on link 'base_link'" in text


def test_world_check_lists_the_plugins_of_world_models():
    report = world_tools.check(os.path.join(SDF, 'camera.world'))
    by_model = {(p['model'], p['kind']): p for p in report['plugins']}
    assert set(by_model) == {('watch_cam', 'camera'), ('tracked_box', 'p3d')}
    assert _params(by_model[('tracked_box', 'p3d')])['bodyName'] == 'body'
    assert by_model[('watch_cam', 'camera')]['sensor'] == 'cam'
    assert report['counts']['error'] == 0, report['findings']
