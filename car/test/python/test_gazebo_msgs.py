"""compat/gazebo_msgs carries gazebo_ros's Noetic interface unchanged: every message and service upstream has,
with upstream's md5sum, in Python and in the generated C++ headers (so a node built against the real gazebo_msgs
and one built against this package talk to each other).

UPSTREAM_MD5 was worked out once from upstream's own definitions: gazebo_ros_pkgs noetic-devel at
f9e1a4607842afa5888ef01de31cd64a1e3e297f, gazebo_msgs/msg/*.msg and srv/*.srv, loaded with genmsg 0.6.0
(genmsg.msg_loader.load_msg_from_file / load_srv_from_file + load_depends against Debian's std_msgs,
geometry_msgs, sensor_msgs and trajectory_msgs 1.13.1) and hashed with genmsg.gentools.compute_md5 -- the hash
rospy and roscpp check when a client connects. test_definitions_hash_as_upstream recomputes the same hash from
compat/'s files at test time, so a changed field fails even before a build.
"""
import os
import re

import pytest

from conftest import REPO, generated_header

COMPAT = os.path.join(REPO, 'compat', 'gazebo_msgs')

UPSTREAM_MD5 = {
    'msg/ContactState': '48c0ffb054b8c444f870cecea1ee50d9',
    'msg/ContactsState': 'acbcb1601a8e525bf72509f18e6f668d',
    'msg/LinkState': '0818ebbf28ce3a08d48ab1eaa7309ebe',
    'msg/LinkStates': '48c080191eb15c41858319b4d8a609c2',
    'msg/ModelState': '9330fd35f2fcd82d457e54bd54e10593',
    'msg/ModelStates': '48c080191eb15c41858319b4d8a609c2',
    'msg/ODEJointProperties': '1b744c32a920af979f53afe2f9c3511f',
    'msg/ODEPhysics': '667d56ddbd547918c32d1934503dc335',
    'msg/PerformanceMetrics': '884f71fd5037b886ec5e126b83c4425a',
    'msg/SensorPerformanceMetric': '01762ded18cfe9ebc7c8222667c99547',
    'msg/WorldState': 'de1a9de3ab7ba97ac0e9ec01a4eb481e',
    'srv/ApplyBodyWrench': '585b9f9618aa0581b207e2f2d90866bc',
    'srv/ApplyJointEffort': 'c0039811b8cc919490b3cff748cdf46b',
    'srv/BodyRequest': '5eade9afe7f232d78005bd0cafeab755',
    'srv/DeleteLight': 'ae11ea8100d536d5b92c2b5917abf912',
    'srv/DeleteModel': '9ce56b4e9e54616de25d796dc972a262',
    'srv/GetJointProperties': '7b30be900f50aa21efec4a0ec92d91c9',
    'srv/GetLightProperties': 'df2cef87e13e2e6990e81e8aaa454c19',
    'srv/GetLinkProperties': '0e06a70386d0ee3fb880c02f23fcd821',
    'srv/GetLinkState': '09d6c98cce97b35f7ab9bd70300657ab',
    'srv/GetModelProperties': '5717f7bd34ed990fa80e28b3015027a3',
    'srv/GetModelState': '4c515e936d3319c9610c559c60bfc3d4',
    'srv/GetPhysicsProperties': '575a5e74786981b7df2e3afc567693a6',
    'srv/GetWorldProperties': '36bb0f2eccf4d8be971410c22818ba3f',
    'srv/JointRequest': '0be1351618e1dc030eb7959d9a4902de',
    'srv/SetJointProperties': '15a76e921b1410c698d82782ea5fa370',
    'srv/SetJointTrajectory': '88f5c10979e3f9649d5ae87a3b12aa65',
    'srv/SetLightProperties': 'e6f13430c57278bb364aca53a1bf5ebf',
    'srv/SetLinkProperties': 'd534ce1b36ee99de0ffa806c3a6348f0',
    'srv/SetLinkState': '8a5146eb66ae4d26b0860b08f3f271be',
    'srv/SetModelConfiguration': '10e3139d3b669c40afc057d38956fff7',
    'srv/SetModelState': '5b3ab0281d4f5445def017e3a2e4a07b',
    'srv/SetPhysicsProperties': '97e2057080558ce4730434b5fae75c91',
    'srv/SpawnModel': '9ed9c82c96abe1a00c3e8cdaeee24413',
}


def _hash_compat():
    import genmsg.gentools as gt
    import genmsg.msg_loader as ml
    search = {'gazebo_msgs': [os.path.join(COMPAT, 'msg')]}
    for p in ('std_msgs', 'geometry_msgs', 'sensor_msgs', 'trajectory_msgs'):
        search[p] = ['/usr/share/%s/msg' % p]
    ctx = ml.MsgContext.create_default()
    out = {}
    for kind in ('msg', 'srv'):
        for f in sorted(os.listdir(os.path.join(COMPAT, kind))):
            path, full = os.path.join(COMPAT, kind, f), 'gazebo_msgs/' + f[:-4]
            spec = (ml.load_msg_from_file if kind == 'msg' else ml.load_srv_from_file)(ctx, path, full)
            ml.load_depends(ctx, spec, search)
            out['%s/%s' % (kind, f[:-4])] = gt.compute_md5(ctx, spec)
    return out


def test_definitions_hash_as_upstream():
    assert _hash_compat() == UPSTREAM_MD5


def test_every_definition_is_built():
    # the package's CMakeLists names every file (a file left out would not be generated)
    text = open(os.path.join(COMPAT, 'CMakeLists.txt')).read()
    for key in UPSTREAM_MD5:
        kind, name = key.split('/')
        assert re.search(r'\b%s\.%s\b' % (name, kind), text), key


@pytest.mark.parametrize('key', sorted(UPSTREAM_MD5))
def test_python_type_matches_upstream(key):
    import importlib
    kind, name = key.split('/')
    cls = getattr(importlib.import_module('gazebo_msgs.' + kind), name)
    assert cls._md5sum == UPSTREAM_MD5[key]
    assert cls._type == 'gazebo_msgs/' + name


@pytest.mark.parametrize('key', sorted(UPSTREAM_MD5))
def test_cpp_header_matches_upstream(key):
    header = generated_header('gazebo_msgs', key.split('/')[1])
    assert os.path.isfile(header), 'catkin generated no %s from compat/gazebo_msgs' % header
    text = open(header).read()
    sums = re.findall(r'return "([0-9a-f]{32})";', text)
    assert UPSTREAM_MD5[key] in sums
