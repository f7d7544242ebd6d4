"""spawn_model's -sdf and -database (gazebo_ros scripts/spawn_model; docs/COMPAT-sdf.md 13)."""
import xml.etree.ElementTree as ET

from car.ros import spawn


def test_sdf_file_goes_to_spawn_sdf_model():
    o = spawn.parse_args('-sdf -file robot.sdf -model r'.split())
    assert (o['format'], o['file']) == ('sdf', 'robot.sdf')
    assert spawn.service_name(o) == '/gazebo/spawn_sdf_model'


def test_urdf_goes_to_spawn_urdf_model():
    o = spawn.parse_args('-urdf -param robot_description -model r -gazebo_namespace /sim/'.split())
    assert spawn.service_name(o) == '/sim/spawn_urdf_model'


def test_database_sends_gazebo_ros_include_document():
    o = spawn.parse_args('-sdf -database sdf_box_bot -model b'.split())
    assert o['database'] == 'sdf_box_bot'
    root = ET.fromstring(spawn.MODEL_DATABASE_TEMPLATE.format(o['database']))
    assert root.tag == 'sdf' and root.get('version') == '1.4'
    assert root.find('world/include/uri').text == 'model://sdf_box_bot'
