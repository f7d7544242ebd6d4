"""The xacro tool: upstream xacro expansion, $(find car), xacro args, and one-line errors."""
import os
import xml.etree.ElementTree as ET

import pytest

from car import xacro_tool
from conftest import DATA, URDF, run_tool


def test_car04_expands_to_the_nine_links(car04_xml):
    names = [l.get('name') for l in ET.fromstring(car04_xml).findall('link')]
    assert names == ['base_footprint', 'base_link', 'left_wheel', 'right_wheel', 'front_wheel', 'back_wheel',
                     'camera', 'support', 'laser']


def test_car04_has_diff_drive_laser_and_kinect_plugins(car04_xml):
    files = [p.get('filename') for p in ET.fromstring(car04_xml).iter('plugin')]
    # camera01.xacro and kinect.xacro each bring a Kinect plug-in on the same sensor name
    assert files == ['libgazebo_ros_diff_drive.so', 'libgazebo_ros_laser.so',
                     'libgazebo_ros_openni_kinect.so', 'libgazebo_ros_openni_kinect.so']


def test_wheel_separation_evaluates_from_car_properties(car04_xml):
    sep = ET.fromstring(car04_xml).find('.//plugin/wheelSeparation').text
    assert float(sep) == pytest.approx(0.2)  # ${base_radius * 2}


def test_find_car_resolves_to_the_package():
    robot = ET.fromstring(xacro_tool.expand(os.path.join(DATA, 'find_car.xacro')))
    # sphere_inertial_matrix from $(find car)/urdf/inertial.xacro: 2 m r^2 / 5
    assert float(robot.find('.//inertia').get('ixx')) == pytest.approx(2 * 1 * 0.01 / 5)


def test_xacro_arg_mapping_overrides_default():
    robot = ET.fromstring(xacro_tool.expand(os.path.join(DATA, 'find_car.xacro'), {'radius': '0.2'}))
    assert float(robot.find('.//sphere').get('radius')) == pytest.approx(0.2)


def test_cli_writes_urdf_to_stdout():
    r = run_tool('xacro', os.path.join(DATA, 'find_car.xacro'), 'radius:=0.3')
    assert r.returncode == 0, r.stderr
    assert float(ET.fromstring(r.stdout).find('.//sphere').get('radius')) == pytest.approx(0.3)


# ---- bad input: one clear line naming file, line and reason ------------------------------------------

def expand_error(name):
    with pytest.raises(xacro_tool.ExpandError) as e:
        xacro_tool.expand(os.path.join(DATA, 'bad', name))
    return e.value


def test_missing_include_names_the_including_file_and_line():
    e = expand_error('missing_include.xacro')
    assert (e.file, e.line) == (os.path.join(DATA, 'bad', 'missing_include.xacro'), 3)
    assert e.reason == 'included file not found: %s' % os.path.join(DATA, 'bad', 'does_not_exist.xacro')


def test_undefined_property_names_file_line_and_name():
    e = expand_error('undefined_property.xacro')
    assert (os.path.basename(e.file), e.line) == ('undefined_property.xacro', 4)
    assert e.reason.startswith("undefined property or name 'base_radius'")


def test_undefined_macro_names_the_macro():
    e = expand_error('undefined_macro.xacro')
    assert (os.path.basename(e.file), e.line) == ('undefined_macro.xacro', 4)
    assert e.reason == "undefined macro 'cylinder_inertial_matrix'"


def test_malformed_xml_names_the_line():
    e = expand_error('malformed.urdf')
    assert (os.path.basename(e.file), e.line) == ('malformed.urdf', 5)
    assert e.reason == 'malformed XML: mismatched tag'


def test_missing_file():
    e = expand_error('no_such_file.xacro')
    assert e.reason == 'no such file'


def test_cli_error_is_one_line_and_nonzero():
    r = run_tool('xacro', os.path.join(DATA, 'bad', 'undefined_property.xacro'))
    assert r.returncode == 2
    assert r.stdout == ''
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1
    assert lines[0].startswith('xacro: error: %s:4: undefined property' % os.path.join(DATA, 'bad',
                                                                                       'undefined_property.xacro'))
