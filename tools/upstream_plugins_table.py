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

# the trajectory each compares, and its tolerance [m] (joint positions: [rad]; f3d: [N]; odometry: the larger of the
# position's distance [m] and the yaw's difference [rad]).
# The drives: the probe publishes the command while the world is paused and waits 0.5 s of wall time before it
# unpauses, so both runs (car's kind through the node's input, upstream's through its own callback-queue thread) hold
# it from the first step: no update of difference in when it acts. Both drive the same motors (ODE's joint motor as
# Joint::SetParam "vel"/"fmax" gives it, car's kinds the same since car's wheel motors pull toward their integrated
# angle only while their target is 0), with the same update clock, so they differ by rounding only: car's motors
# anchored during the 11 ms before the first update (target 0, wheels at rest: a pull of the solver's residual, far
# below a micrometre), upstream's planar_move turning its command by a float yaw (cosf, sinf: a relative 6e-8, 2e-8 m
# over the 3.2 m it moves). 1e-5 m (a hundredth of a millimetre) bounds that; one update's travel (5 mm for the diff
# drive) is what a real difference in the rule would show.
ROUNDING = 1e-5
TOL = {
    'diff_drive': ROUNDING,
    'skid_steer_drive': ROUNDING,
    'planar_move': ROUNDING,
    # upstream's p3d reads the pose in WorldUpdateBegin, before the step its stamp counts (Gazebo's order); car's p3d
    # after it: one step apart, 1 ms of the box's 0.32 m/s (yaw: 0.2 rad/s, 0.2 mrad)
    'p3d': math.hypot(0.3, 0.1) * 0.001 + ROUNDING,
    'tricycle_drive': ROUNDING,
    'force': 1.0 * 0.001,                      # about 1 m/s after 2 s: one step of 1 ms
    'f3d': 1e-9,                               # the wrench added: the same numbers
    'joint_state_publisher': 1e-6,             # no command: the arm's joints as the physics leaves them
    'joint_pose_trajectory': 1e-6,             # positions set, not integrated
    # the box pulled 0.5 m by a critically damped spring (kl 200 N/m, 1 kg: w = 14.1 rad/s) moves at most
    # 0.5 w / e = 2.6 m/s: one step of 1 ms, if one run takes up the target a step later, is 2.6 mm
    'hand_of_god': 0.5 * math.sqrt(200.0) / math.e * 0.001 + ROUNDING,
    'template': 0.5 * math.sqrt(200.0) / math.e * 0.001 + ROUNDING,
    'vacuum_gripper': 0.5 * math.sqrt(200.0) / math.e * 0.001 + ROUNDING,
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
                # odometry (x, y, z, yaw): the position's distance and the yaw's difference wrapped into [-pi, pi]
                # (the probe's yaw, atan2 of products of two quaternion components, is the same for q and -q)
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
