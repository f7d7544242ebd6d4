"""compat/controller_manager_msgs and compat/control_msgs carry ros_control's and control_msgs' Noetic interfaces:
every definition with upstream's md5sum (Python classes and generated C++ headers), so controller_manager clients
and FollowJointTrajectory clients built against the real packages talk to car.

UPSTREAM_MD5 was worked out once from upstream's own files: ros-controls/ros_control noetic-devel
controller_manager_msgs/{msg,srv} (release 0.20.0) and ros-controls/control_msgs kinetic-devel control_msgs/{msg,srv}
(release 1.5.2, the Noetic one; the FollowJointTrajectory action's three sections as messages), loaded with genmsg
0.6.0 against Debian's std_msgs, geometry_msgs, trajectory_msgs and actionlib_msgs, hashed with
genmsg.gentools.compute_md5. test_definitions_hash_as_upstream recomputes them from compat/'s files.
"""
import os
import re

import pytest

from conftest import REPO, generated_header

UPSTREAM_MD5 = {
    'controller_manager_msgs/msg/ControllerState': 'aeb6b261d97793ab74099a3740245272',
    'controller_manager_msgs/msg/ControllerStatistics': '697780c372c8d8597a1436d0e2ad3ba8',
    'controller_manager_msgs/msg/ControllersStatistics': 'a154c347736773e3700d1719105df29d',
    'controller_manager_msgs/msg/HardwareInterfaceResources': 'f25b55cbf1d1f76e82e5ec9e83f76258',
    'controller_manager_msgs/srv/ListControllerTypes': 'c1d4cd11aefa9f97ba4aeb5b33987f4e',
    'controller_manager_msgs/srv/ListControllers': '1341feb2e63fa791f855565d0da950d8',
    'controller_manager_msgs/srv/LoadController': '647e5c54b8d6468952d8d31f1efe96c0',
    'controller_manager_msgs/srv/ReloadControllerLibraries': '40e8c411fd1797d2e2c486018f846040',
    'controller_manager_msgs/srv/SwitchController': 'b29a7abc673b2c54c14b54e50f8d06a5',
    'controller_manager_msgs/srv/UnloadController': '647e5c54b8d6468952d8d31f1efe96c0',
    'control_msgs/msg/GripperCommand': '680acaff79486f017132a7f198d40f08',
    'control_msgs/msg/JointControllerState': '987ad85e4756f3aef7f1e5e7fe0595d1',
    'control_msgs/msg/JointJog': '1685da700c8c2e1254afc92a5fb89c96',
    'control_msgs/msg/JointTolerance': 'f544fe9c16cf04547e135dd6063ff5be',
    'control_msgs/msg/JointTrajectoryControllerState': '10817c60c2486ef6b33e97dcd87f4474',
    'control_msgs/msg/PidState': 'b138ec00e886c10e73f27e8712252ea6',
    'control_msgs/msg/FollowJointTrajectoryFeedback': '10817c60c2486ef6b33e97dcd87f4474',
    'control_msgs/msg/FollowJointTrajectoryGoal': '69636787b6ecbde4d61d711979bc7ecb',
    'control_msgs/msg/FollowJointTrajectoryResult': '493383b18409bfb604b4e26c676401d2',
    'control_msgs/srv/QueryCalibrationState': '28af3beedcb84986b8e470dc5470507d',
    'control_msgs/srv/QueryTrajectoryState': 'ec93cdecbd8062d761aa52b7c90cd44b',
}


def _hash_compat():
    import genmsg.gentools as gt
    import genmsg.msg_loader as ml
    import tempfile
    act = tempfile.mkdtemp()
    # the action's goal, result and feedback sections as messages (what genaction generates from them)
    text = open(os.path.join(REPO, 'compat', 'control_msgs', 'action', 'FollowJointTrajectory.action')).read()
    for part, body in zip(('Goal', 'Result', 'Feedback'), text.split('\n---')):
        with open(os.path.join(act, 'FollowJointTrajectory%s.msg' % part), 'w') as f:
            f.write(body.lstrip('\n'))
    search = {p: ['/usr/share/%s/msg' % p] for p in ('std_msgs', 'geometry_msgs', 'trajectory_msgs', 'actionlib_msgs')}
    search['controller_manager_msgs'] = [os.path.join(REPO, 'compat', 'controller_manager_msgs', 'msg')]
    search['control_msgs'] = [os.path.join(REPO, 'compat', 'control_msgs', 'msg'), act]
    ctx = ml.MsgContext.create_default()
    out = {}
    for key in UPSTREAM_MD5:
        pkg, kind, name = key.split('/')
        if name.startswith('FollowJointTrajectory'):
            path = os.path.join(act, name + '.msg')
        else:
            path = os.path.join(REPO, 'compat', pkg, kind, name + '.' + kind)
        spec = (ml.load_msg_from_file if kind == 'msg' else ml.load_srv_from_file)(ctx, path, pkg + '/' + name)
        ml.load_depends(ctx, spec, search)
        out[key] = gt.compute_md5(ctx, spec)
    return out


def test_definitions_hash_as_upstream():
    assert _hash_compat() == UPSTREAM_MD5


@pytest.mark.parametrize('key', sorted(UPSTREAM_MD5))
def test_python_type_matches_upstream(key):
    import importlib
    pkg, kind, name = key.split('/')
    cls = getattr(importlib.import_module(pkg + '.' + kind), name)
    assert cls._md5sum == UPSTREAM_MD5[key]
    assert cls._type == pkg + '/' + name


@pytest.mark.parametrize('key', sorted(UPSTREAM_MD5))
def test_cpp_header_matches_upstream(key):
    pkg, _, name = key.split('/')
    header = generated_header(pkg, name)
    assert os.path.isfile(header), 'catkin generated no %s from compat/%s' % (header, pkg)
    assert UPSTREAM_MD5[key] in re.findall(r'return "([0-9a-f]{32})";', open(header).read())
