#!/usr/bin/env python3
"""rostest: node /gazebo offers exactly the topics and services docs/COMPAT-dropins.md lists for its
enable_ros_network value (~network param of this test), with their types: publishers, subscribers, services."""
import os
import re
import time
import unittest

import rosgraph
import rospy
import rosservice
import rostest

# the repository's docs/, beside car/ (car/test/ros/../../../docs); a copy of the tests beside an install finds
# them at share/car/test/ros/../../docs (tools/test_workspace.sh)
_HERE = os.path.dirname(os.path.abspath(__file__))
DOC = next((p for p in (os.path.join(_HERE, '..', '..', '..', 'docs', 'COMPAT-dropins.md'),
                        os.path.join(_HERE, '..', '..', 'docs', 'COMPAT-dropins.md')) if os.path.exists(p)),
           os.path.join(_HERE, '..', '..', '..', 'docs', 'COMPAT-dropins.md'))


def expected(network):
    """(kind, name, type) rows of the table that follows the doc's 'With `enable_ros_network:=VALUE`' line."""
    text = open(DOC).read()
    start = text.index('With `enable_ros_network:=%s`' % ('true' if network else 'false'))
    rows, seen_table = set(), False
    for line in text[start:].splitlines()[1:]:
        m = re.match(r'^\| (published|subscribed|service) \| (\S+) \| (\S+) \|$', line)
        if m:
            rows.add(m.groups())
            seen_table = True
        elif seen_table and not line.startswith('|'):
            break
    return rows


def actual(node):
    master = rosgraph.Master('/dropin_api')
    pubs, subs, srvs = master.getSystemState()
    types = dict(master.getTopicTypes())
    rows = set()
    for kind, entries in (('published', pubs), ('subscribed', subs)):
        for name, nodes in entries:
            if node in nodes:
                rows.add((kind, name, types.get(name, '?')))
    for name, nodes in srvs:
        if node in nodes:
            rows.add(('service', name, rosservice.get_service_type(name)))
    return rows


def wait_ready(network, timeout=60.0):
    """Waits (wall time, a bound for a hang) for node /gazebo's last advertisement: set_parameters with the ROS API
    on, /clock with it off (docs/COMPAT-dropins.md); fails naming it."""
    last = ('service', '/gazebo/set_parameters', 'dynamic_reconfigure/Reconfigure') if network else \
        ('published', '/clock', 'rosgraph_msgs/Clock')
    deadline = time.time() + timeout
    while last not in actual('/gazebo'):
        if time.time() > deadline:
            raise AssertionError('node /gazebo has not offered %s %s within %.0f s' % (last[0], last[1], timeout))
        time.sleep(0.2)


class ApiLists(unittest.TestCase):
    """The exact lists, for either value; a subclass sets network and adds what that value means."""
    network = None

    def test_lists_and_types_match_the_doc(self):
        want = expected(self.network)
        # the doc's table was read: with enable_ros_network false it has 4 rows (/clock, /rosout, the two logger
        # services), with it true more
        self.assertGreaterEqual(len(want), 4)
        wait_ready(self.network)
        model = rospy.get_param('~wait_model', '')
        if model:
            # a spawned robot (car_extras false) adds nothing to the node's lists
            from gazebo_msgs.srv import GetWorldProperties
            props = rospy.ServiceProxy('/gazebo/get_world_properties', GetWorldProperties)
            deadline = time.time() + 60
            while model not in props().model_names and time.time() < deadline:
                time.sleep(0.2)
            self.assertIn(model, props().model_names)
        # wait_ready saw the last advertisement; a second lets the master's list settle
        time.sleep(1.0)
        got = actual('/gazebo')
        self.assertEqual(sorted(got - want), [], 'offered but not in the doc')
        self.assertEqual(sorted(want - got), [], 'in the doc but not offered')


class DropinApiOn(ApiLists):
    """enable_ros_network true (dropin_api.test, dropin_extras.test)."""
    network = True

    def test_spawn_sdf_model_offered(self):
        wait_ready(True)
        self.assertIn(('service', '/gazebo/spawn_sdf_model', 'gazebo_msgs/SpawnModel'), actual('/gazebo'))

    def test_reconfigure_reads_the_world_and_sets_gravity_through_set_physics_properties(self):
        from dynamic_reconfigure.client import Client
        from gazebo_msgs.srv import GetPhysicsProperties
        client = Client('/gazebo', timeout=60)
        c = client.get_configuration(timeout=10)
        # the first configuration is the world's: empty world, step 0.001 s, gravity -9.8; rtf 0 -> max_update_rate 0
        self.assertEqual((c['time_step'], c['gravity_z'], c['max_update_rate']), (0.001, -9.8, 0.0))
        c = client.update_configuration({'gravity_z': -3.7})
        get = rospy.ServiceProxy('/gazebo/get_physics_properties', GetPhysicsProperties)
        self.assertEqual(get().gravity.z, -3.7)
        self.assertEqual(c['gravity_z'], -3.7)
        # a new step size is refused by set_physics_properties (car keeps the world's): the world's value comes back
        c = client.update_configuration({'time_step': 0.002})
        self.assertEqual((c['time_step'], get().time_step), (0.001, 0.001))


class DropinApiOff(ApiLists):
    """enable_ros_network false (dropin_api_off.test): what "off" means beyond the exact lists."""
    network = False

    def test_no_spawn_service(self):
        wait_ready(False)
        # upstream's gazebo_ros advertises its services only with the ROS network on
        self.assertEqual(sorted(r[1] for r in actual('/gazebo') if r[0] == 'service' and 'spawn' in r[1]), [])

    def test_no_reconfigure_server(self):
        wait_ready(False)
        names = {r[1] for r in actual('/gazebo')}
        # upstream's server waits for the physics services, which never come with the ROS API off
        self.assertEqual(sorted(names & {'/gazebo/set_parameters', '/gazebo/parameter_descriptions',
                                         '/gazebo/parameter_updates'}), [])


if __name__ == '__main__':
    rospy.init_node('dropin_api')
    rostest.rosrun('car', 'dropin_api', DropinApiOn if rospy.get_param('~network') else DropinApiOff)
