#!/usr/bin/env python3
"""The web view in a headless browser (Debian's chromium + chromedriver through python3-selenium; software WebGL).

The page of `sim.launch web:=true` is opened with the camera straight above the spawn point (test/ros/web_view.test:
position (0, 0, 6) m, looking at (0, 0, 0), 60 deg vertical field of view, +y up in the image), so a point (x, y, z)
of the odom frame lands on pixel u = W/2 + f x / (6 - z), v = H/2 - f y / (6 - z), f = (H/2) / tan(30 deg), W x H the
canvas. The car's visuals are orange (car.xacro's 0.8 0.3 0.1 and the lidar support's 0.8 0.5 0), the lidar points
magenta: the test finds them by colour.
"""
import io
import math
import os
import sys
import time
import unittest

import numpy as np
import rospy
import rostest
from gazebo_msgs.srv import GetModelState
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry
from rosgraph_msgs.msg import Clock

from simtest import Recorder, receive_all

CAM_HEIGHT, FOV_DEG = 6.0, 60.0  # [m], [deg]: as web_view.test sets ~camera
MODEL = 'mycar'


def browser():
    from selenium import webdriver
    from selenium.webdriver.chrome.options import Options
    from selenium.webdriver.chrome.service import Service
    o = Options()
    for a in ('--headless=new', '--no-sandbox', '--disable-dev-shm-usage', '--use-gl=angle', '--use-angle=swiftshader',
              '--enable-unsafe-swiftshader', '--window-size=900,600'):
        o.add_argument(a)
    d = webdriver.Chrome(service=Service('/usr/bin/chromedriver'), options=o)
    d.set_page_load_timeout(300)
    return d


def screenshot(driver):
    """The page as an (H, W, 3) uint8 array and the canvas rectangle (left, top, width, height) in its pixels."""
    from PIL import Image
    img = np.asarray(Image.open(io.BytesIO(driver.get_screenshot_as_png())).convert('RGB'))
    r = driver.execute_script(
        "const c = [...document.querySelectorAll('canvas')].sort((a, b) => b.width * b.height - a.width * a.height)[0];"
        "const r = c.getBoundingClientRect(); return [r.left, r.top, r.width, r.height, window.devicePixelRatio];")
    s = r[4]
    return img, (r[0] * s, r[1] * s, r[2] * s, r[3] * s)


def orange(img):
    """Pixels of the car's orange (hue 5..45 deg, saturated, not dark): (N, 2) (u, v)."""
    f = img.astype(np.float64)
    r, g, b = f[..., 0], f[..., 1], f[..., 2]
    mx, mn = f.max(axis=2), f.min(axis=2)
    sat = (mx - mn) / np.maximum(mx, 1.0)
    hue = np.degrees(np.arctan2(math.sqrt(3) * (g - b), 2 * r - g - b)) % 360.0
    m = (r == mx) & (sat > 0.55) & (mx > 90) & (hue > 5) & (hue < 45)
    v, u = np.nonzero(m)
    return np.stack([u, v], axis=1)


def magenta(img):
    f = img.astype(np.int32)
    v, u = np.nonzero((f[..., 0] > 180) & (f[..., 2] > 180) & (f[..., 1] < 90))
    return np.stack([u, v], axis=1)


def project(rect, x, y, z=0.0):
    left, top, w, h = rect
    f = (h / 2.0) / math.tan(math.radians(FOV_DEG) / 2.0)
    return np.array([left + w / 2.0 + f * x / (CAM_HEIGHT - z), top + h / 2.0 - f * y / (CAM_HEIGHT - z)])


def wait_for(cond, timeout, what):
    """Polls cond() (wall time: the browser renders in wall time) until it returns something truthy. A browser too
    busy to answer in time (software WebGL on a loaded machine: chromedriver's 'Timed out receiving message from
    renderer') is asked again."""
    from selenium.common.exceptions import TimeoutException
    deadline = time.time() + timeout
    while time.time() < deadline:
        try:
            r = cond()
        except TimeoutException:
            continue
        if r is not None and r is not False:
            return r
        time.sleep(0.5)
    raise AssertionError('timed out waiting for %s' % what)


def view_subscriptions():
    """The topics /web_view subscribes to now, from the master."""
    import rosgraph
    _, subs, _ = rosgraph.Master('/test_web_view').getSystemState()
    return [t for t, nodes in subs if '/web_view' in nodes]


def sensor_subscriptions():
    """The sensor topics /web_view subscribes to now."""
    return sorted(t for t in view_subscriptions() if t in ('/scan', '/camera/depth/points', '/camera/rgb/image_raw'))


class WebViewTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_web_view')
        cls.url = wait_for(lambda: rospy.get_param('/web_view/url', None), 120, 'the web view URL')
        rospy.wait_for_service('/gazebo/get_model_state', timeout=120)
        cls.state = rospy.ServiceProxy('/gazebo/get_model_state', GetModelState)
        wait_for(lambda: cls.state(MODEL, '').success, 120, 'the car to spawn')
        # cmd_vel messages with the wall time [s, monotonic] each arrived at, and every /clock message with its own
        # arrival: a command's arrival in sim time is bracketed by the clocks read just before and just after it
        cls.cmds, cls.cmd_walls, cls.clocks = [], [], []

        def cmd(m):
            cls.cmd_walls.append(time.monotonic())
            cls.cmds.append(m)

        def clock(m):
            cls.clocks.append((time.monotonic(), m.clock.to_sec()))
        rospy.Subscriber('/cmd_vel', Twist, cmd, tcp_nodelay=True)
        receive_all(rospy.Subscriber('/clock', Clock, clock, queue_size=None, tcp_nodelay=True))
        # the car's ground truth (p3d, 100 Hz), for the speed of one press
        cls.truth = Recorder('/gazebo/ground_truth/%s' % MODEL, Odometry)
        # the view is in its loop (it subscribes to /gazebo/model_states just before it), with no browser yet
        wait_for(lambda: '/gazebo/model_states' in view_subscriptions(), 120, "the view's model_states subscription")
        cls.sensor_subs_before = sensor_subscriptions()
        cls.driver = browser()
        cls.driver.get(cls.url)

    @classmethod
    def tearDownClass(cls):
        if cls.driver is not None:
            cls.driver.quit()

    def car_in_image(self, driver):
        """The centroid of the orange pixels within 100 px of where the car should be drawn, once at least 30 are
        drawn there, else None. (The window keeps out the page's own orange: a notice about software WebGL, and
        box_house's brick-red walls, which are 1.5 m and more from the car.)"""
        img, rect = screenshot(driver)
        p = self.state(MODEL, '').pose.position
        want = project(rect, p.x, p.y, 0.1)
        px = orange(img)
        px = px[np.abs(px - want).max(axis=1) <= 100]
        return (px.mean(axis=0), want) if len(px) >= 30 else None

    def test_0_no_browser_no_sensor_subscriptions(self):
        # the simulator renders a sensor only while someone subscribes: a view nobody looks at costs it nothing
        self.assertEqual(self.sensor_subs_before, [])

    def test_1_car_is_drawn_where_the_simulation_says(self):
        centroid, want = wait_for(lambda: self.car_in_image(self.driver), 300, 'the car in the page')
        # 15 px = 0.15 m at this scale (f / 5.9 m = 88 px/m on a 600 px canvas): the centroid of the body and the
        # lidar support, which sit within 0.1 m of the base's origin
        self.assertLess(np.linalg.norm(centroid - want), 15.0, 'car drawn at %s, simulation says %s' % (centroid, want))

    def test_2_lidar_points_are_drawn(self):
        def enough():
            img, rect = screenshot(self.driver)
            px = magenta(img)
            return (px, rect) if len(px) >= 100 else None
        px, rect = wait_for(enough, 300, 'lidar points in the page')
        # with a browser looking, the view holds the scan (the cloud and the image only for a sample at a time)
        self.assertIn('/scan', sensor_subscriptions())
        # they lie on the walls around the car, not on the car: most farther than 0.5 m from it
        p = self.state(MODEL, '').pose.position
        f = (rect[3] / 2.0) / math.tan(math.radians(FOV_DEG) / 2.0) / CAM_HEIGHT
        d = np.linalg.norm(px - project(rect, p.x, p.y), axis=1) / f
        self.assertGreater(np.median(d), 0.5)

    def sim_time_at(self, wall):
        """(lo, hi): the sim times [s] of the last /clock read before wall and the first read after it."""
        lo = max((c for w, c in self.clocks if w <= wall), default=None)
        hi = min((c for w, c in self.clocks if w >= wall), default=None)
        return lo, hi

    def test_3_one_forward_press_drives_the_speed_for_the_span_its_command_was_live(self):
        from selenium.webdriver.common.by import By
        button = wait_for(lambda: ([b for b in self.driver.find_elements(By.TAG_NAME, 'button')
                                    if b.text.strip() == 'Forward'] or [None])[0], 60, 'the Forward button')
        x0 = self.state(MODEL, '').pose.position.x
        n0 = len(self.cmds)
        button.click()
        wait_for(lambda: any(c.linear.x > 0.0 for c in self.cmds[n0:]), 30, 'a forward cmd_vel')
        # the dead-man window (1 s of wall time) closes: a zero command follows
        wait_for(lambda: self.cmds[-1].linear.x == 0.0 and any(c.linear.x > 0.0 for c in self.cmds[n0:]), 30,
                 'the dead-man stop')
        cmds, walls = self.cmds[n0:], self.cmd_walls[n0:]
        first = next(i for i, c in enumerate(cmds) if c.linear.x > 0.0)
        stop = next(i for i in range(first, len(cmds)) if cmds[i].linear.x == 0.0)
        v = cmds[first].linear.x
        self.assertAlmostEqual(v, 0.5)  # the speed slider's default
        # What one press does. The drive (car.xacro: wheelAcceleration 1.8 m/s^2, updateRate 100 Hz) ramps the
        # wheels by 1.8 m/s^2 times upstream's 0.011 s per 0.01 s update (docs/COMPAT-plugins.md), so at a =
        # 1.98 m/s^2, up from the update after the command reaches the simulator and down from the update after the
        # stop does: the ramp up loses v^2 / 2a and the ramp down gains it back, so at rest the car has gone v * T, T
        # the sim-time span the command was live in the simulator. Wait for rest: the stop's arrival, plus
        # v / a = 0.25 s of ramp, plus 0.5 s.
        a = 1.8 * 0.011 / 0.01

        def at_rest():
            hi = self.sim_time_at(walls[stop])[1]
            return hi is not None and self.clocks[-1][1] >= hi + v / a + 0.5
        wait_for(at_rest, 120, 'sim time 0.75 s past the stop command')
        x1 = self.state(MODEL, '').pose.position.x
        # T from the simulator's own ground truth: each speed sample u on a ramp dates that ramp's start, up at
        # t - u / a and down at t - (v - u) / a (the median of the samples between 20 % and 80 % of v). The
        # commands' arrivals here, bracketed by /clock, are not the simulator's: under load the two processes read
        # the same message tens of milliseconds apart (0.03 s seen at load 6), so they are only reported.
        since = self.sim_time_at(walls[first])[0] - 0.5
        truth = [m for m in self.truth.msgs if since <= m.header.stamp.to_sec()]
        t = np.array([m.header.stamp.to_sec() for m in truth])
        x = np.array([m.pose.pose.position.x for m in truth])
        tm, u = 0.5 * (t[1:] + t[:-1]), np.diff(x) / np.diff(t)
        peak = int(np.argmax(u))
        up = (u > 0.2 * v) & (u < 0.8 * v) & (np.arange(len(u)) < peak)
        down = (u > 0.2 * v) & (u < 0.8 * v) & (np.arange(len(u)) > peak)
        self.assertGreater(up.sum(), 3, 'ground truth on the ramp up (%d samples in all)' % len(u))
        self.assertGreater(down.sum(), 3, 'ground truth on the ramp down (%d samples in all)' % len(u))
        span = float(np.median(tm[down] - (v - u[down]) / a) - np.median(tm[up] - u[up] / a))
        start_lo, start_hi = self.sim_time_at(walls[first])
        stop_lo, stop_hi = self.sim_time_at(walls[stop])
        arrivals = 0.5 * ((stop_lo + stop_hi) - (start_lo + start_hi))
        # Tolerance: the ramps move in steps of a * 0.01 s at the drive's updates, so each ramp's dated start is
        # within one update (0.01 s) of where the speed's staircase began; times v, plus 1 mm for the wheels (no
        # slip: the tyres' mu 1 allows 9.8 m/s^2, the ramp asks 1.98; the motors' anchor creeps 0.3 mm per 10 s).
        self.assertGreater(span, 0.0)
        self.assertAlmostEqual(x1 - x0, v * span, delta=v * 0.02 + 0.001,
                               msg='one press: live %.3f s of sim time in the simulator (%.3f s between the '
                                   'arrivals here), %d commands' % (span, arrivals, stop - first + 1))

    def test_4_closing_the_browser_leaves_the_sim_running_and_a_new_one_sees_the_scene(self):
        # close the first browser: the simulation's clock goes on
        type(self).driver.quit()
        type(self).driver = None
        clock = []
        sub = rospy.Subscriber('/clock', Clock, clock.append)
        t = rospy.get_time()
        wait_for(lambda: clock and clock[-1].clock.to_sec() > t + 0.5, 120, 'the clock after the browser closed')
        sub.unregister()
        # a second browser gets the whole scene (the car where the simulation has it now)
        second = browser()
        try:
            second.get(self.url)
            centroid, want = wait_for(lambda: self.car_in_image(second), 300, 'the car in a second page')
            self.assertLess(np.linalg.norm(centroid - want), 15.0)
        finally:
            second.quit()


if __name__ == '__main__':
    rostest.rosrun('car', 'web_view_browser', WebViewTest)
