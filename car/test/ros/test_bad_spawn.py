#!/usr/bin/env python3
"""rostest: every URDF and xacro case of the adversarial corpus through spawn_model against a running node:
exit code and message asserted, spawn_model bounded in memory and time, and the node still answers after each."""
import os
import sys
import unittest

import rospy
import rostest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), 'python'))
import bad_corpus  # noqa: E402
from gazebo_services import DeleteModel, GetWorldProperties  # noqa: E402
import simtest  # noqa: E402


class BadSpawnTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_bad_spawn')
        rospy.wait_for_service('/gazebo/get_world_properties', timeout=60)
        cls.props = rospy.ServiceProxy('/gazebo/get_world_properties', GetWorldProperties)
        cls.delete = rospy.ServiceProxy('/gazebo/delete_model', DeleteModel)

    def test_every_urdf_and_xacro_case(self):
        import tempfile
        from car import xacro_tool
        tmp = tempfile.mkdtemp(prefix='bad_spawn_')
        failures, tried = [], 0
        for i, (name, entry) in enumerate(bad_corpus.cases(('urdf', 'xacro'))):
            path = bad_corpus.path_of(name, entry, tmp)
            if entry['kind'] == 'xacro':
                try:
                    xml = xacro_tool.expand(path)
                except xacro_tool.ExpandError:
                    continue  # nothing to spawn: the xacro tool refused it (asserted in test_bad_corpus.py)
                path = os.path.join(tmp, name + '.urdf')
                with open(path, 'w', encoding='utf-8') as f:
                    f.write(xml)
            model = 'case_%d' % i
            tried += 1
            p = bad_corpus.run_bounded([sys.executable, simtest.car_program('spawn_model'),
                                        '-urdf', '-file', path, '-model', model, '-timeout', '30'])
            out = p.stdout + p.stderr
            want_ok = entry.get('spawn', entry['exit'] == 0)
            if p.returncode != (0 if want_ok else 1):
                failures.append('%s: exit %d, wanted %d: %s' % (name, p.returncode, 0 if want_ok else 1, out[-600:]))
            elif not want_ok:
                for m in bad_corpus.messages(entry, 'spawn'):
                    if m not in out:
                        failures.append('%s: %r not in %s' % (name, m, out[-600:]))
            if bad_corpus.PASSWD_MARK in out:
                failures.append('%s: /etc/passwd leaked' % name)
            # the node is still there, and a refused model left nothing behind
            names = self.props().model_names
            if want_ok:
                self.delete(model)
            elif model in names:
                failures.append('%s: refused, yet %s is in the world' % (name, model))
        self.assertGreaterEqual(tried, 45)
        self.assertEqual(failures, [], '\n'.join(failures))


if __name__ == '__main__':
    rostest.rosrun('car', 'bad_spawn', BadSpawnTest)
