"""What the out-of-CI probes share (tools/kobuki_probe.py, tools/mimic_probe.py; run on /usr/bin/python3): a wait
on sim time with a wall-clock guard that fails naming what it waited for, and one result line per check
(CHECK | FIGURE | ok/FAIL)."""
import sys
import time

import rospy


def wait_until(tool, what, cond, sim_s, wall_s=120.0):
    """Until cond() or sim_s of sim time passed; False (with a message) when the wall guard ends it first."""
    end_sim = rospy.get_time() + sim_s
    end_wall = time.time() + wall_s
    while not cond() and rospy.get_time() < end_sim:
        if time.time() > end_wall:
            print("%s: gave up waiting for %s (wall guard %.0f s)" % (tool, what, wall_s), file=sys.stderr)
            return False
        time.sleep(0.01)
    return cond()


def run(main, results):
    """Runs main(), prints the result lines whatever happened, and exits 0 when every check passed."""
    try:
        main()
    finally:
        print("\n".join(results.lines))
    sys.exit(0 if results.all_ok() else 1)


class Results:
    """The checks' lines, in order."""

    def __init__(self):
        self.lines = []

    def check(self, name, figure, ok):
        self.lines.append("%s | %s | %s" % (name, figure, "ok" if ok else "FAIL"))

    def all_ok(self):
        return bool(self.lines) and all(line.endswith("ok") for line in self.lines)
