#!/usr/bin/env python3
"""rostest: a world that fails to load stops the simulator with the file and the reason."""
import os
import subprocess
import unittest

import rospkg
import rostest
import simtest

DATA = os.path.join(rospkg.RosPack().get_path('car'), 'test', 'data')


def run_sim(world):
    node = simtest.car_program('sim_node')
    return subprocess.run([node, '__name:=bad_world_sim', '_world_name:=' + world], capture_output=True, text=True,
                          timeout=60)


class BadWorldTest(unittest.TestCase):
    def test_missing_world_file(self):
        path = os.path.join(DATA, 'nope.world')
        r = run_sim(path)
        self.assertEqual(r.returncode, 1)
        self.assertIn('car: cannot load the world: %s: cannot open file' % path, r.stderr)

    def test_dynamic_link_without_mass(self):
        path = os.path.join(DATA, 'bad', 'massless.world')
        r = run_sim(path)
        self.assertEqual(r.returncode, 1)
        self.assertIn('%s: model[crate]/link[body]/inertial: a dynamic link needs a mass > 0' % path, r.stderr)


if __name__ == '__main__':
    rostest.rosrun('car', 'test_bad_world', BadWorldTest)
