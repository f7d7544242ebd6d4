"""The model check on the seed car and on broken inputs."""
import json
import os

import numpy as np
import pytest

from car import model_check
from conftest import DATA, URDF, run_tool

CAR04 = os.path.join(URDF, 'car_camera_lidar04.xacro')


@pytest.fixture(scope='module')
def report(car04_xml):
    return model_check.check_text(car04_xml, 'car04')


def finding(report, code, element):
    hits = [f for f in report['findings'] if f['code'] == code and f['element'] == element]
    assert len(hits) == 1, [(f['code'], f['element']) for f in report['findings']]
    return hits[0]


def test_camera_inertia_is_flagged_with_the_correct_tensor(report):
    f = finding(report, 'inertia-mismatch', 'link[camera]/inertial/inertia')
    assert f['severity'] == 'warning'
    m, l, w, h = 0.01, 0.02, 0.05, 0.05  # box x y z
    # Box_inertial_matrix gives ixx = m(h^2 + l^2)/12: x and z are swapped
    np.testing.assert_allclose(f['declared'], np.diag([m * (h * h + l * l) / 12, m * (w * w + l * l) / 12,
                                                       m * (w * w + h * h) / 12]), rtol=1e-5)
    np.testing.assert_allclose(f['expected'], np.diag([m * (w * w + h * h) / 12, m * (l * l + h * h) / 12,
                                                       m * (l * l + w * w) / 12]), rtol=1e-5)


def test_wheel_inertia_about_the_wrong_axis_is_flagged(report):
    # the wheel cylinder is turned to the y axis by rpy (pi/2 0 0), the macro puts m r^2/2 on z
    f = finding(report, 'inertia-mismatch', 'link[left_wheel]/inertial/inertia')
    m, r = 0.05, 0.0325
    assert f['expected'][1][1] == pytest.approx(m * r * r / 2, rel=1e-5)


def test_base_link_inertia_matches_its_cylinder(report):
    assert not [f for f in report['findings'] if f['element'] == 'link[base_link]/inertial/inertia']


def test_caster_axes_reported_as_normalised(report):
    for joint in ('front2link', 'back2link'):
        f = finding(report, 'axis-normalised', 'joint[%s]/axis' % joint)
        assert '(0.57735 0.57735 0.57735)' in f['message']


def test_out_of_range_colour_reported(report):
    f = finding(report, 'colour-range', 'link[camera]/visual/material[no]/color')
    assert "rgba '3 3 3 0.3'" in f['message']


def test_plugins_listed_with_defaults(report):
    diff = [p for p in report['plugins'] if p['kind'] == 'diff_drive'][0]
    params = {p['key']: p for p in diff['params']}
    assert params['odometrySource']['value'] == 'world' and params['odometrySource']['default']
    assert params['wheelTorque']['value'] == '30' and not params['wheelTorque']['default']


def test_seed_car_has_no_errors(report):
    assert report['counts']['error'] == 0
    assert model_check.exit_code(report, strict=False) == 0


def test_strict_fails_on_the_seed_warnings(report):
    assert model_check.exit_code(report, strict=True) == 1


def test_clean_model_has_no_findings():
    with open(os.path.join(DATA, 'clean.urdf')) as f:
        report = model_check.check_text(f.read(), 'clean.urdf')
    assert report['findings'] == []


def test_cli_json_parses_and_exits_zero():
    r = run_tool('check_model', CAR04, '--json')
    assert r.returncode == 0, r.stderr
    data = json.loads(r.stdout)
    assert data['robot'] == 'mycar'
    # 9 links as written; base_link, camera, support and laser hang on fixed joints and are lumped into
    # base_footprint as Gazebo does, leaving the root and the four wheel/caster links
    assert len(data['links']) == 5
    assert sorted(l['name'] for l in data['lumped']) == ['base_link', 'camera', 'laser', 'support']
    assert data['exit_code'] == 0


def test_cli_human_output_shows_both_tensors():
    r = run_tool('check_model', CAR04)
    assert r.returncode == 0
    assert 'link[camera]/inertial/inertia' in r.stdout
    assert 'expected [4.16667e-06 0 0; 0 2.41667e-06 0; 0 0 2.41667e-06] kg m^2' in r.stdout


def test_cli_strict_exits_one():
    assert run_tool('check_model', CAR04, '--strict').returncode == 1


# ---- bad input ----------------------------------------------------------------------------------------

def test_zero_mass_is_an_error_exit_2():
    r = run_tool('check_model', os.path.join(DATA, 'bad', 'zero_mass.urdf'))
    assert r.returncode == 2
    # mass 0 is massless for Gazebo: on the root (nothing fixed to it) nothing of the robot is left
    assert ("error   link[base_link] (line 3): root link 'base_link' has no mass (no <inertial> or mass 0), also "
            "after lumping the links fixed to it; Gazebo models nothing of this robot") in r.stdout


def test_zero_axis_is_an_error_exit_2():
    r = run_tool('check_model', os.path.join(DATA, 'bad', 'zero_axis.urdf'))
    assert r.returncode == 2
    assert 'error   joint[wheel_joint]/axis (line 9): axis has zero length' in r.stdout


def test_missing_wheel_joint_is_an_error_exit_2():
    r = run_tool('check_model', os.path.join(DATA, 'bad', 'missing_wheel_joint.urdf'))
    assert r.returncode == 2
    assert ("gazebo/plugin[diff]/leftJoint (line 7): joint 'left2link' not found in the model "
            "(plug-in 'diff', libgazebo_ros_diff_drive.so)") in r.stdout


def test_missing_file_exit_2_one_line():
    path = os.path.join(DATA, 'nope.urdf')
    r = run_tool('check_model', path)
    assert r.returncode == 2
    assert r.stderr.strip() == 'check_model: error: %s: no such file or directory' % path


def test_malformed_xml_exit_2_names_line():
    path = os.path.join(DATA, 'bad', 'malformed.urdf')
    r = run_tool('check_model', path)
    assert r.returncode == 2
    assert r.stderr.strip() == ('check_model: error: %s:3: malformed XML: mismatched element: '
                                'XMLElement name=link' % path)


def test_xacro_error_exit_2():
    r = run_tool('check_model', os.path.join(DATA, 'bad', 'undefined_property.xacro'), '--json')
    assert r.returncode == 2
    assert "undefined property or name 'base_radius'" in json.loads(r.stdout)['error']


# ---- the import as Gazebo does it (docs/COMPAT-spawn.md) ------------------------------------------------

ZOO = os.path.join(DATA, 'zoo')


def check_zoo(name):
    path = os.path.join(ZOO, name)
    with open(path) as f:
        return model_check.check_text(f.read(), path)


def test_lumped_links_are_reported_as_notes():
    r = check_zoo('lumping.urdf')
    f = finding(r, 'link-lumped', 'link[camera_link]')
    assert f['severity'] == 'info'
    assert f['line'] == 9
    assert {l['name']: l['parent'] for l in r['lumped']} == {'camera_link': 'base', 'imu_link': 'base', 'tool': 'base'}


def test_dropped_link_is_a_warning_naming_its_subtree():
    r = check_zoo('lumping.urdf')
    f = finding(r, 'link-dropped', 'link[flap]')
    assert f['severity'] == 'warning'
    assert r['dropped'] == [{'name': 'flap', 'joint': 'flap_joint', 'subtree': ['flap_tip']}]
    assert model_check.format_report(r).count('dropped (no mass on a moving joint, as Gazebo): flap (with flap_tip)') == 1


def test_world_anchor_is_reported():
    r = check_zoo('arm.urdf')
    assert r['world_joints'] == ['world_fix']
    assert finding(r, 'world-anchor', 'joint[world_fix]')['severity'] == 'info'
    assert 'anchored to the world by: world_fix' in model_check.format_report(r)


def test_unresolved_mesh_is_an_error():
    xml = ("<robot name='m'><link name='a'><inertial><mass value='1'/><inertia ixx='1' ixy='0' ixz='0' iyy='1' "
           "iyz='0' izz='1'/></inertial><collision><geometry><mesh filename='meshes/nowhere.stl'/></geometry>"
           "</collision></link></robot>")
    r = model_check.check_text(xml, os.path.join(ZOO, 'virtual.urdf'))
    f = finding(r, 'mesh-unresolved', 'link[a]/collision[0]/mesh')
    assert f['severity'] == 'error'
    assert "mesh 'meshes/nowhere.stl' not found" in f['message']
    assert model_check.exit_code(r, strict=False) == 2


def test_missing_visual_mesh_is_a_warning_naming_the_file():
    # issue 29 item 3: Gazebo simulates a robot whose visual mesh is missing, so the check warns (exit 0)
    path = os.path.join(DATA, 'meshes', 'visual_mesh_missing.urdf')
    with open(path) as f:
        r = model_check.check_text(f.read(), path)
    f = finding(r, 'visual-mesh-missing', 'link[base_link]/visual[body]/mesh')
    assert f['severity'] == 'warning'
    assert f['message'] == ("mesh 'waffle_base.stl' not found (looked in %s/waffle_base.stl); the visual is not "
                            "drawn (the model is simulated: physics and sensors use its collisions)"
                            % os.path.join(DATA, 'meshes'))
    assert model_check.exit_code(r, strict=False) == 0


def test_resolved_zoo_mesh_is_not_reported():
    # cube.obj sits in test/data/zoo/meshes/: the relative URI resolves against the file's folder
    xml = ("<robot name='m'><link name='a'><inertial><mass value='1'/><inertia ixx='1' ixy='0' ixz='0' iyy='1' "
           "iyz='0' izz='1'/></inertial><collision><geometry><mesh filename='meshes/cube.obj'/></geometry>"
           "</collision></link></robot>")
    r = model_check.check_text(xml, os.path.join(ZOO, 'virtual.urdf'))
    assert [f for f in r['findings'] if f['code'] == 'mesh-unresolved'] == []


def test_unreadable_attribute_value_is_reported_with_its_line():
    xml = ("<robot name='m'>\n<link name='a'><inertial><mass value='1'/><inertia ixx='1' ixy='0' ixz='0' "
           "iyy='1' iyz='0' izz='1'/></inertial></link>\n<gazebo reference='a'>\n<mu1 value='slippery'/>\n"
           "</gazebo></robot>")
    r = model_check.check_text(xml, 'values.urdf')
    f = finding(r, 'gazebo-value', 'gazebo[a]/mu1')
    assert (f['severity'], f['line'], f['message']) == ('error', 4, "'slippery' is not a number")


def test_attribute_form_values_are_read():
    xml = ("<robot name='m'><link name='a'><inertial><mass value='1'/><inertia ixx='1' ixy='0' ixz='0' "
           "iyy='1' iyz='0' izz='1'/></inertial></link><gazebo reference='a'><mu1 value='0.5'/>"
           "<kp value='1e7'/></gazebo></robot>")
    r = model_check.check_text(xml, 'values.urdf')
    assert [f for f in r['findings'] if f['severity'] == 'error'] == []


def test_huge_mass_is_named_by_the_mass_range_finding_not_a_nan_percentage():
    # issue 29 item 5: a 1e300 kg link made the inertia comparison print "nan% off"
    path = os.path.join(DATA, 'bad', 'mass_huge.urdf')
    with open(path) as f:
        r = model_check.check_text(f.read(), path)
    assert [f for f in r['findings'] if f['code'] == 'inertia-mismatch'] == []
    f = finding(r, 'mass-range', 'link[wheel]/inertial/mass')
    assert f['message'] == ('mass 1e+300 kg is outside 1e-06..1e+06 kg (a unit mistake? the solver loses accuracy '
                            'at such masses)')
    assert 'nan' not in model_check.format_report(r)
