"""World tools: include resolution and flattening, the include rule shared with the core, and the checks."""
import math
import os
import xml.etree.ElementTree as ET

import pytest

from car import _core, world_tools
from car.paths import package_dir
from conftest import DATA, ROOT

WORLDS = os.path.join(DATA, 'worlds')
INCLUDES = os.path.join(WORLDS, 'includes.world')


@pytest.fixture(autouse=True)
def test_models(monkeypatch):
    monkeypatch.setenv('GAZEBO_MODEL_PATH', os.path.join(DATA, 'models'))
    monkeypatch.setenv('ROS_PACKAGE_PATH', ROOT + ':' + os.environ.get('ROS_PACKAGE_PATH', ''))


def models_of(desc):
    return {m['name']: (m['static'], [round(v, 9) for v in m['pose']['xyz']], round(m['pose']['rpy'][2], 9))
            for m in desc['models']}


def flat(path, tmp_path):
    out = tmp_path / 'flat.world'
    out.write_text(world_tools.flatten_to_string(path))
    return str(out)


def test_flattened_world_has_exactly_the_expected_models(tmp_path):
    world = ET.parse(flat(INCLUDES, tmp_path)).getroot().find('world')
    assert [m.get('name') for m in world.findall('model')] == [
        'ground_plane', 'crate_a', 'crate_b', 'crate_c', 'shelf']  # shelf's include is flattened into it
    assert [l.get('name') for l in world.findall('light')] == ['sun']
    assert world.find('include') is None


def test_include_overrides_name_pose_and_static(tmp_path):
    models = models_of(_core.load_world_file(flat(INCLUDES, tmp_path)))
    assert models['crate_a'] == (False, [1.0, 2.0, 0.0], 0.5)    # <pose> replaces the model's own 9 9 9
    assert models['crate_b'] == (True, [-1.0, 0.0, 0.0], 0.0)    # file:// relative to the world, <static> true
    assert models['crate_c'] == (False, [0.0, -2.0, 0.0], 0.0)   # package://


def links_of(desc, model):
    m = [m for m in desc['models'] if m['name'] == model][0]
    return {l['name']: ([round(v, 9) for v in l['world_pose']['xyz']], round(l['world_pose']['rpy'][2], 9))
            for l in m['links']}


def test_an_include_inside_a_model_is_flattened_into_it(tmp_path):
    # Gazebo 11's sdformat 9 (addNestedModel): the included crate's link is shelf's own, named top_crate::body
    # (docs/COMPAT-sdf.md 16a). shelf at (3, 0, 0) turned 90 deg; top_crate at (0.2, 0, 0.51) in the shelf frame and its
    # body 0.25 m above it: (0.2, 0, 0.76) in shelf, (3 - 0, 0 + 0.2, 0.76) in the world
    for desc in (_core.load_world_file(INCLUDES), _core.load_world_file(flat(INCLUDES, tmp_path))):
        assert models_of(desc)['shelf'][0] is True  # static, as shelf is
        links = links_of(desc, 'shelf')
        assert sorted(links) == ['board', 'top_crate::body']
        xyz, yaw = links['top_crate::body']
        assert xyz == pytest.approx([3.0, 0.2, 0.76])
        assert yaw == pytest.approx(math.pi / 2)


def test_the_flattener_renames_an_included_models_names(tmp_path):
    # what addNestedModel writes: the included model's link named top_crate::body in shelf, no model top_crate
    world = ET.parse(flat(INCLUDES, tmp_path)).getroot().find('world')
    shelf = [m for m in world.findall('model') if m.get('name') == 'shelf'][0]
    assert [l.get('name') for l in shelf.findall('link')] == ['board', 'top_crate::body']
    assert shelf.find('model') is None


def test_a_parent_with_no_link_of_its_own_is_left_out_of_the_flat_world(tmp_path):
    # libsdformat 12 refuses a model without a link; the hoisted board keeps everything shelf simulated
    src = tmp_path / 'nested.world'
    src.write_text('<sdf version="1.7"><world name="w"><model name="shelf"><pose>1 0 0 0 0 0</pose>'
                   '<model name="board"><pose>0 0 0.5 0 0 0</pose><link name="l"/></model></model></world></sdf>')
    flat_path = flat(str(src), tmp_path)
    assert [m.get('name') for m in ET.parse(flat_path).getroot().find('world').findall('model')] == ['shelf::board']
    assert models_of(_core.load_world_file(flat_path))['shelf::board'] == (False, [1.0, 0.0, 0.5], 0.0)


def test_model_config_picks_the_highest_sdf_version(tmp_path):
    world = ET.parse(flat(INCLUDES, tmp_path)).getroot().find('world')
    crate = [m for m in world.findall('model') if m.get('name') == 'crate_a'][0]
    assert crate.find('link').get('name') == 'body'  # model.sdf (1.6), not model-1_5.sdf


def test_simulator_reads_the_world_as_the_flattener_writes_it(tmp_path):
    # one rule: the core resolving the includes itself == the core reading the flattened file
    assert models_of(_core.load_world_file(INCLUDES)) == models_of(_core.load_world_file(flat(INCLUDES, tmp_path)))


def test_flatten_keeps_the_declared_encoding(tmp_path):
    # 'm\xe9' in ISO-8859-1 is the byte 0xE9; read as UTF-8 it would be malformed
    world = tmp_path / 'latin1.world'
    world.write_bytes(b'<?xml version="1.0" encoding="ISO-8859-1"?>\n<sdf version="1.6"><world name="w">'
                      b'<model name="m\xe9"><static>true</static><link name="l"/></model></world></sdf>\n')
    assert _core.flatten_world(str(world)).startswith(b'<?xml version="1.0" encoding="ISO-8859-1"?>')
    assert [m.get('name') for m in world_tools.flatten(str(world)).getroot().iter('model')] == ['m\u00e9']


def test_state_poses_are_applied_and_the_block_dropped(tmp_path):
    world = ET.parse(flat(os.path.join(ROOT, 'worlds', 'box_house.world'), tmp_path)).getroot().find('world')
    assert world.find('state') is None
    box = [m for m in world.findall('model') if m.get('name') == 'unit_box_0'][0]
    assert box.findtext('pose').split()[:3] == ['-4.96407', '-2.00353', '0.499995']


def test_model_path_order_is_the_same_in_both(monkeypatch, tmp_path):
    (tmp_path / 'ground_plane').mkdir()
    monkeypatch.setenv('GAZEBO_MODEL_PATH', str(tmp_path))
    assert world_tools.resolve_uri('model://ground_plane', '.') == str(tmp_path / 'ground_plane')
    assert _core.resolve_uri('model://ground_plane') == str(tmp_path / 'ground_plane')
    monkeypatch.setenv('GAZEBO_MODEL_PATH', '')
    # the built-in models where car's files are: the source package, or car/data/ in a pip install
    builtin = os.path.realpath(os.path.join(package_dir(), 'models', 'ground_plane'))
    assert os.path.realpath(world_tools.resolve_uri('model://ground_plane', '.')) == builtin
    assert os.path.realpath(_core.resolve_uri('model://ground_plane')) == builtin


# ---- bad input -----------------------------------------------------------------------------------------

def error_of(name):
    with pytest.raises(world_tools.WorldError) as e:
        world_tools.flatten(os.path.join(WORLDS, 'bad', name))
    return e.value


def test_include_without_uri():
    e = error_of('no_uri.world')
    assert (e.element, e.reason) == ('world[bad]/include[0]', '<include> has no <uri>')


def test_include_of_a_missing_model():
    e = error_of('missing_model.world')
    assert e.element == 'world[bad]/include[0]/uri'
    assert e.reason.startswith("cannot find 'model://no_such_model' (model path: ")


def check_of(name):
    return world_tools.check(os.path.join(WORLDS, 'bad', name))['findings']


def test_malformed_pose():
    (f,) = check_of('bad_pose.world')
    assert (f['severity'], f['element']) == ('error', 'world[bad]/model[post]/pose')
    assert f['message'] == "pose '1 2 three 0 0 0' is not 6 numbers (x y z roll pitch yaw)"


def test_non_finite_pose():
    (f,) = check_of('pose_nan.world')
    assert (f['severity'], f['code'], f['element']) == ('error', 'pose-malformed', 'world[bad]/model[post]/pose')
    assert f['message'] == "pose 'nan 0 0.5 0 0 0' has a non-finite value"


def test_unknown_geometry():
    (f,) = check_of('unknown_geometry.world')
    assert (f['severity'], f['element']) == ('error', 'world[bad]/model[blob]/link[l]/collision[c]/geometry/torus')
    # SDF 1.9's geometry.sdf, sorted
    assert f['message'] == ('unknown geometry <torus> (SDF knows box, capsule, cylinder, ellipsoid, empty, heightmap, '
                            'image, mesh, plane, polyline, sphere)')


def test_empty_geometry():
    (f,) = check_of('empty_geometry.world')
    assert (f['severity'], f['code'], f['element']) == ('error', 'geometry-empty',
                                                        'world[bad]/model[ghost]/link[l]/collision[c]/geometry')
    assert f['message'] == '<geometry> holds no shape'


def test_unsimulated_geometry_is_a_warning():
    f = [f for f in check_of('unsimulated_geometry.world') if f['code'] == 'geometry-unsimulated']
    assert [(x['severity'], x['element'], x['message']) for x in f] == [
        ('warning', 'world[bad]/model[pill]/link[l]/collision[c]/geometry/capsule',
         '<capsule> is not simulated by car; ignored')]


def test_mesh_without_uri():
    (f,) = check_of('mesh_no_uri.world')
    assert (f['element'], f['message']) == ('world[bad]/model[statue]/link[l]/visual[v]/geometry/mesh',
                                            '<mesh> has no <uri>')


def test_massless_dynamic_link():
    (f,) = check_of('massless.world')
    assert f['severity'] == 'error'
    assert 'a dynamic link needs a mass > 0' in f['message']


def test_inertia_against_the_shape():
    (f,) = check_of('wrong_inertia.world')
    assert (f['severity'], f['element']) == ('warning', 'world[bad]/model[cube]/link[body]/inertial/inertia')
    assert [round(f['expected'][i][i], 6) for i in range(3)] == [0.166667] * 3


def test_check_reads_the_world_in_one_core_call(monkeypatch):
    # the flattener, the rules and the loader are the core's, behind car._core.check_world; Python parses nothing
    calls = []
    real = _core.check_world
    monkeypatch.setattr(_core, 'check_world', lambda path: calls.append(path) or real(path))
    for name in ('flatten_world', 'load_world_string', 'load_world_file'):
        monkeypatch.setattr(_core, name, lambda *a, **k: pytest.fail('check parsed the world again'))
    path = os.path.join(ROOT, 'worlds', 'box_house.world')
    world_tools.check(path)
    assert calls == [path]


def test_map_reads_the_world_in_one_core_call(monkeypatch):
    # world_tool map and plot: the flattener and the loader behind one call, no text through Python's parser
    calls = []
    real = _core.load_flattened_world
    monkeypatch.setattr(_core, 'load_flattened_world', lambda path, w=None: calls.append(path) or real(path, w))
    for name in ('flatten_world', 'load_world_string', 'load_world_file'):
        monkeypatch.setattr(_core, name, lambda *a, **k: pytest.fail('map parsed the world again'))
    monkeypatch.setattr(ET, 'XMLParser', lambda *a, **k: pytest.fail('map parsed the world in Python'))
    world_tools.load(INCLUDES, [])
    assert calls == [INCLUDES]


def test_load_gives_the_world_the_simulator_reads():
    # includes resolved by sdformat (the simulator) == includes expanded by the flattener, then loaded
    assert models_of(world_tools.load(INCLUDES)) == models_of(_core.load_world_file(INCLUDES))


def test_load_leaves_a_missing_include_out_with_its_warning():
    warnings = []
    world = world_tools.load(os.path.join(WORLDS, 'bad', 'missing_model.world'), warnings)
    assert world['models'] == []
    assert [(w['code'], w['element']) for w in warnings] == [('include-missing', 'world[bad]/include[0]/uri')]


def test_load_reads_iso_8859_1_as_its_declaration_says(tmp_path):
    world = tmp_path / 'latin1.world'
    world.write_bytes(b'<?xml version="1.0" encoding="ISO-8859-1"?>\n<sdf version="1.6"><world name="w">'
                      b'<model name="m\xe9"><static>true</static><link name="l"/></model></world></sdf>\n')
    assert [m['name'] for m in world_tools.load(str(world))['models']] == ['m\u00e9']


def test_load_of_a_byte_that_is_not_text(tmp_path):
    # no declaration: UTF-8, where the lone byte 0xE9 is not text
    world = tmp_path / 'not_text.world'
    world.write_bytes(b'<sdf version="1.6"><world name="w">'
                      b'<model name="m\xe9"><static>true</static><link name="l"/></model></world></sdf>\n')
    with pytest.raises(world_tools.WorldError) as e:
        world_tools.load(str(world))
    assert (e.value.file, e.value.element) == (str(world), '')
    assert e.value.reason == ('not UTF-8 text (byte 0xe9; car reads worlds in UTF-8, and in ISO-8859-1 where their '
                              'declaration says so)')


def test_box_house_is_clean():
    assert world_tools.check(os.path.join(ROOT, 'worlds', 'box_house.world'))['findings'] == []
