#!/usr/bin/env python3
"""The web view's cost: the full stack's real-time factor (sim.launch at rtf:=0: the seed car in box_house with its
lidar, camera and Kinect) without the web view, with it serving no browser, then with one headless Chromium connected
(software WebGL, on this machine), each measured over the same wall time in one run; and the default pace (rtf:=1)
with a browser connected, which should hold 1.00.

  bench/bench_web.py [--seconds 20] [--json FILE]

Prints sim seconds per wall second for each and the ratios. The view runs in its own process, drops frames, and
subscribes to sensors only while a browser looks (the depth cloud and the image sampled a few times a second), so
'view, no browser' / 'no view' should be about 1; what a browser costs at rtf:=0 is mostly the CPU its software
WebGL takes from the simulator on a small machine.
"""
import argparse
import json
import os
import socket
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def free_port():
    s = socket.socket()
    s.bind(('127.0.0.1', 0))
    p = s.getsockname()[1]
    s.close()
    return p


def rtf_over(seconds):
    """Sim seconds per wall second over `seconds` of wall time, from /clock."""
    import rospy
    from rosgraph_msgs.msg import Clock
    last = []
    sub = rospy.Subscriber('/clock', Clock, lambda m: last.append(m.clock.to_sec()), queue_size=1)
    while not last:
        time.sleep(0.1)
    s0, w0 = last[-1], time.monotonic()
    time.sleep(seconds)
    s1, w1 = last[-1], time.monotonic()
    sub.unregister()
    return (s1 - s0) / (w1 - w0)


def measure(port, web, seconds, browser, rtf=0):
    """One sim.launch at rtf:=`rtf` against the roscore on `port`; its real-time factor."""
    import rospy
    env = dict(os.environ, ROS_MASTER_URI='http://127.0.0.1:%d' % port)
    if rospy.has_param('/web_view/url'):
        rospy.delete_param('/web_view/url')
    launch = subprocess.Popen(['roslaunch', 'car', 'sim.launch', 'rtf:=%g' % rtf, 'web:=%s' % web, 'web_port:=0'], env=env,
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    driver = None
    try:
        deadline = time.time() + 180
        while web == 'true' and not rospy.has_param('/web_view/url') and time.time() < deadline:
            time.sleep(0.5)
        time.sleep(5)  # the robot spawned and its sensors running
        if browser:
            sys.path.insert(0, os.path.join(ROOT, 'test', 'ros'))
            from test_web_view import browser as make_browser
            driver = make_browser()
            driver.get(rospy.get_param('/web_view/url'))
            time.sleep(10)  # the scene loaded
        return rtf_over(seconds)
    finally:
        if driver is not None:
            driver.quit()
        launch.terminate()
        launch.wait()


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('--seconds', type=float, default=20.0)
    ap.add_argument('--json')
    a = ap.parse_args()
    port = free_port()
    os.environ['ROS_MASTER_URI'] = 'http://127.0.0.1:%d' % port
    core = subprocess.Popen(['roscore', '-p', str(port)], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    rows = {}
    try:
        import rospy
        time.sleep(3)
        rospy.init_node('bench_web', anonymous=True, disable_signals=True)
        for key, web, browser, rtf in (('no_view', 'false', False, 0), ('view_no_browser', 'true', False, 0),
                                       ('view_one_browser', 'true', True, 0),
                                       ('view_one_browser_at_rtf_1', 'true', True, 1)):
            rows[key] = measure(port, web, a.seconds, browser, rtf)
            print('%-22s real-time factor %.2f' % (key, rows[key]), flush=True)
    finally:
        core.terminate()
        core.wait()
    rows['ratio_browser_vs_view'] = rows['view_one_browser'] / rows['view_no_browser']
    rows['ratio_view_vs_none'] = rows['view_no_browser'] / rows['no_view']
    print('one browser / view without browser: %.2f; view / no view: %.2f; at rtf:=1 with a browser: %.3f' % (
        rows['ratio_browser_vs_view'], rows['ratio_view_vs_none'], rows['view_one_browser_at_rtf_1']))
    if a.json:
        with open(a.json, 'w') as f:
            json.dump(rows, f, indent=1, sort_keys=True)


if __name__ == '__main__':
    main()
