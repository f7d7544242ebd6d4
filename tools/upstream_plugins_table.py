#!/usr/bin/env python3
"""The table of tools/upstream_plugins.sh, from its workspace: per plug-in, whether upstream's source built (else its
first compiler error), whether the node ran it from its library, and how its run compares with car's native kind on
the same robot and commands: topics, services, TF edges, frames, and the trajectory at the stamps both runs share up
to the scenario's end.

  upstream_plugins_table.py WORKSPACE PLUGIN... (reads WORKSPACE/built.txt: PLUGIN|yes or no|first error)
"""
import glob
import json
import math
import os
import re
import sys

# the trajectory each compares, and its tolerance [m] (joint positions: [rad]; f3d: [N]), derived from the plug-in's
# rates: the two runs may differ by when a command first acts, at most one update of the plug-in, so by the distance
# covered in one update
TOL = {
    'diff_drive': 0.5 / 100,                   # 0.5 m/s, odometry at 100 Hz
    'skid_steer_drive': 0.3 / 100,             # 0.3 m/s, 100 Hz
    'planar_move': math.hypot(0.3, 0.1) / 20,  # 0.32 m/s, odometry at 20 Hz
    'p3d': math.hypot(0.3, 0.1) / 20,          # the planar_move's motion sampled by p3d: one planar update
    'tricycle_drive': 0.4 / 100,               # 0.4 m/s, 100 Hz
    'force': 1.0 * 0.001,                      # about 1 m/s after 2 s: one step of 1 ms
    'f3d': 1e-9,                               # the wrench added: the same numbers
    'joint_state_publisher': 1e-6,             # no command: the arm's joints as the physics leaves them
    'joint_pose_trajectory': 1e-6,             # positions set, not integrated
    'hand_of_god': 0.002,                      # at most about 2 m/s: one step of 1 ms
    'template': 0.002, 'vacuum_gripper': 0.002,
}
# what each compares: car's ground truth of the robot (stamped with sim time), p3d's own output, f3d's own output,
# the joint states
KEY = {'joint_state_publisher': '/robot/joint_states', 'joint_pose_trajectory': '/robot/joint_states',
       'f3d': '/f3d', 'p3d': '/truth'}
ODOMETRY = {'/gazebo/ground_truth/robot', '/truth', '/odom'}
SECONDS = {'force': 2.0, 'f3d': 2.0, 'joint_state_publisher': 2.0, 'joint_pose_trajectory': 2.0,
           'hand_of_god': 3.0, 'template': 3.0, 'vacuum_gripper': 3.0}


def load(ws, p, mode):
    f = os.path.join(ws, '%s.%s.json' % (p, mode))
    return json.load(open(f)) if os.path.exists(f) else None


def frames(d):
    return sorted({'%s %s>%s' % (t, s[1], s[2]) for t, ss in d['samples'].items() for s in ss if s[1] is not None})


def loaded(ws, p):
    """Whether the node logged the library as running (its rosout log: the screen log may be cut at exit)."""
    log = open(os.path.join(ws, '%s.upstream.node.log' % p), errors='replace').read()
    m = re.search(r'logging to (\S+)/roslaunch-', log)
    texts = [log] + ([open(f, errors='replace').read() for f in glob.glob(m.group(1) + '/*.log')] if m else [])
    return any(("(libgazebo_ros_%s.so) runs from its library" % p) in t for t in texts)


def main():
    ws, plugins = sys.argv[1], sys.argv[2:]
    built = {}
    for line in open(os.path.join(ws, 'built.txt')):
        p, ok, why = line.rstrip('\n').split('|', 2)
        built[p] = (ok == 'yes', why)
    rows = []
    for p in plugins:
        ok, why = built[p]
        if not ok:
            rows.append((p, 'no: ' + why, '', '', ''))
            continue
        a, b = load(ws, p, 'native'), load(ws, p, 'upstream')
        if a is None or b is None:
            rows.append((p, 'yes', 'probe failed (%s run)' % ('native' if a is None else 'upstream'), '', ''))
            continue
        diffs = []
        for what in ('topics', 'services', 'tf'):
            if a[what] != b[what]:
                only_a = sorted(set(map(str, a[what])) - set(map(str, b[what])))
                only_b = sorted(set(map(str, b[what])) - set(map(str, a[what])))
                diffs.append('%s: car only %s, upstream only %s' % (what, only_a or '-', only_b or '-'))
        fa, fb = frames(a), frames(b)
        if fa != fb:
            diffs.append('frames: car only %s, upstream only %s' % (sorted(set(fa) - set(fb)) or '-',
                                                                     sorted(set(fb) - set(fa)) or '-'))
        key = KEY.get(p, '/gazebo/ground_truth/robot')
        end = SECONDS.get(p, 10.0) * 1e9
        sa = {s[0]: s[3] for s in a['samples'].get(key, []) if s[0] is not None and s[0] <= end}
        sb = {s[0]: s[3] for s in b['samples'].get(key, []) if s[0] is not None and s[0] <= end}
        common = sorted(set(sa) & set(sb))
        if common:
            def gap(u, v):
                # odometry (x, y, z, yaw): the position's distance and the yaw's difference, wrapped
                if key in ODOMETRY:
                    return max(math.dist(u[:3], v[:3]), abs(math.remainder(u[3] - v[3], 2 * math.pi)))
                return max([abs(x - y) for x, y in zip(u, v)] or [0.0])
            worst = max(gap(sa[t], sb[t]) for t in common)
            traj = '%s, %d stamps: largest difference %.2g (tolerance %.2g)' % (key, len(common), worst, TOL[p])
            if worst > TOL[p]:
                diffs.append('trajectory beyond its tolerance')
        else:
            traj = '%s: no stamp in common (car %d, upstream %d samples)' % (key, len(sa), len(sb))
        rows.append((p, 'yes', 'runs from its library' if loaded(ws, p) else 'NOT run from its library', traj,
                     'same' if not diffs else '; '.join(diffs)))
    print('| plug-in | builds unchanged | upstream run | trajectory | compared with car\'s kind |')
    print('|---|---|---|---|---|')
    for r in rows:
        print('| %s |' % ' | '.join(r))


if __name__ == '__main__':
    main()
