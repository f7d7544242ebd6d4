"""web_view: the simulation in a browser (car.web_view.WebScene fed from ROS, like rviz).

  rosrun car web_view [_host:=127.0.0.1] [_port:=8080] [_world:=FILE] [_fixed_frame:=odom] [_cloud_budget:=20000]
                      [_robots:=NAME[,NAME...]] [_scan_topic:=/scan] [_cloud_topic:=/camera/depth/points]
                      [_image_topic:=/camera/rgb/image_raw] [_cmd_vel:=cmd_vel] [_rate:=10]
                      [_cloud_rate:=2] [_image_rate:=5]
                      [_camera:="PX PY PZ LX LY LZ [FOV_DEG [UX UY UZ]]"]

Reads robot_description (one robot, named by ~robots, default the first model /gazebo/model_states lists that is
not in the world file), poses every link from TF in the fixed frame, the world's models from the SDF file (moving
ones follow /gazebo/model_states), /scan as points, the depth cloud (thinned to ~cloud_budget points), the colour
image, /clock for sim time and the real-time factor; the drive panel publishes geometry_msgs/Twist on cmd_vel at
~rate while a command is live and calls /gazebo/pause_physics, /unpause_physics and /reset_world. It runs in its
own process and drops frames (queue size 1, newest wins); browsers may come and go.
The simulator renders a sensor only while someone subscribes to it (as gazebo_ros's camera and depth plug-ins do),
so the view subscribes to the sensor topics only while a browser is connected, and to the heavy ones (the depth
cloud, the image) only long enough to take one message, at most ~cloud_rate / ~image_rate times per wall second:
with no browser the simulation runs as without the view, with one it renders a few clouds a second, not every one.
~camera is the view every new browser starts with (position and look-at point in the fixed frame [m], vertical field
of view [deg], image-up direction). The URL is printed and set as the parameter ~url.
"""
from __future__ import annotations

import math
import os
import struct
import sys
import threading
import time

import numpy as np


def _T(tf):
    t, q = tf.transform.translation, tf.transform.rotation
    from car.web_view import _rot
    T = np.eye(4)
    T[:3, :3] = _rot(q.x, q.y, q.z, q.w)
    T[:3, 3] = (t.x, t.y, t.z)
    return T


def cloud_xyz_rgb(msg):
    """(N, 3) float32 points and (N, 3) uint8 colours (or None) of a PointCloud2 with float32 x, y, z [and rgb]."""
    fields = {f.name: f for f in msg.fields}
    n = msg.width * msg.height
    buf = np.frombuffer(msg.data, dtype=np.uint8).reshape(n, msg.point_step) if n else np.zeros((0, msg.point_step),
                                                                                                 np.uint8)
    xyz = np.stack([buf[:, fields[k].offset:fields[k].offset + 4].copy().view('<f4').ravel() for k in 'xyz'], axis=1)
    rgb = None
    if 'rgb' in fields:
        o = fields['rgb'].offset
        rgb = buf[:, [o + 2, o + 1, o]].copy()
    return xyz, rgb


def image_rgb(msg):
    """(H, W, 3) uint8 from a sensor_msgs/Image in rgb8, bgr8 or mono8; None otherwise."""
    a = np.frombuffer(msg.data, dtype=np.uint8)
    if msg.encoding in ('rgb8', 'bgr8'):
        img = a.reshape(msg.height, msg.step)[:, :msg.width * 3].reshape(msg.height, msg.width, 3)
        return img[:, :, ::-1].copy() if msg.encoding == 'bgr8' else img.copy()
    if msg.encoding == 'mono8':
        g = a.reshape(msg.height, msg.step)[:, :msg.width]
        return np.repeat(g[:, :, None], 3, axis=2)
    return None


class Sampled:
    """A subscription held only while wanted, taking at most one message per `period` wall seconds (period 0:
    held continuously). Its own thread lets go of the topic as soon as a sampled message arrives, so the simulator
    renders about one frame per sample, not every frame until the next poll."""

    def __init__(self, topic, msg_type, period, **kw):
        self.topic, self.msg_type, self.period, self.kw = topic, msg_type, period, kw
        self.msg, self.wanted, self.got = None, False, False
        self.cond = threading.Condition()
        if topic:
            threading.Thread(target=self._run, name='web_view ' + topic, daemon=True).start()

    def _cb(self, msg):
        with self.cond:
            self.msg, self.got = msg, True
            self.cond.notify_all()

    def _run(self):
        import rospy
        while not rospy.is_shutdown():
            with self.cond:
                self.cond.wait_for(lambda: self.wanted, timeout=1.0)
                if not self.wanted:
                    continue
                self.got = False
            start = time.monotonic()
            sub = rospy.Subscriber(self.topic, self.msg_type, self._cb, queue_size=1, **self.kw)
            with self.cond:
                if self.period > 0:
                    self.cond.wait_for(lambda: self.got or not self.wanted)
                else:
                    self.cond.wait_for(lambda: not self.wanted)
            sub.unregister()
            time.sleep(max(0.0, start + self.period - time.monotonic()))

    def poll(self, wanted):
        """The newest message since the last poll (or None); `wanted` says whether to hold the topic."""
        with self.cond:
            msg, self.msg = self.msg, None
            if wanted != self.wanted:
                self.wanted = wanted
                self.cond.notify_all()
        return msg


def replay_main(argv) -> int:
    """web_view --replay OUTDIR SCENARIO: car batch runs in the browser, without ROS."""
    import argparse
    from car.web_view import Replay
    ap = argparse.ArgumentParser(prog='web_view --replay', description='Replays car batch runs in a browser.')
    ap.add_argument('outdir', help='the OUTDIR of car batch (holds trajectories.parquet)')
    ap.add_argument('scenario', help='the scenario YAML the runs came from')
    ap.add_argument('--runs', default='', help='comma-separated run ids, as in runs.parquet (default: all)')
    ap.add_argument('--speed', type=float, default=1.0, help='x real time')
    ap.add_argument('--loop', action='store_true')
    ap.add_argument('--host', default='127.0.0.1')
    ap.add_argument('--port', type=int, default=8080)
    a = ap.parse_args(argv)
    runs = [r for r in a.runs.split(',') if r] or None
    r = Replay(a.outdir, a.scenario, runs, host=a.host, port=a.port)
    print('car web view (replay of %d runs): %s' % (len(r.runs), r.web.url), flush=True)
    r.play(a.speed, a.loop)
    r.web.stop()
    return 0


def main(argv=None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    if argv[:1] == ['--replay']:
        return replay_main(argv[1:])
    import rospy
    import tf2_ros
    from geometry_msgs.msg import Twist
    from rosgraph_msgs.msg import Clock
    from sensor_msgs.msg import Image, LaserScan, PointCloud2
    from std_srvs.srv import Empty

    from car import _core
    from car.web_view import WebScene

    rospy.init_node('web_view')
    # a viewer yields the CPU to the simulation: on a busy machine the view drops frames, the simulation does not slow
    nice = int(rospy.get_param('~nice', 10))
    if nice > 0:
        os.nice(nice)
    host, port = rospy.get_param('~host', '127.0.0.1'), int(rospy.get_param('~port', 8080))
    fixed = rospy.get_param('~fixed_frame', 'odom')
    world_file = rospy.get_param('~world', '')
    rate = float(rospy.get_param('~rate', 10.0))
    web = WebScene(host=host, port=port, cloud_budget=int(rospy.get_param('~cloud_budget', 20000)),
                   hold=float(rospy.get_param('~hold', 1.0)))
    cam = [float(v) for v in str(rospy.get_param('~camera', '-4 -4 5 0 0 0')).split()]
    if len(cam) not in (6, 7, 10):
        rospy.logfatal('web_view: ~camera: want 6, 7 or 10 numbers (position, look-at [, fov [, up]]), got %r',
                       rospy.get_param('~camera'))
        return 2
    web.look_from(cam[0:3], cam[3:6], cam[6] if len(cam) > 6 else None,
                  tuple(cam[7:10]) if len(cam) == 10 else (0.0, 0.0, 1.0))
    world_models = set()
    if world_file:
        desc = _core.load_world_file(world_file)
        web.add_world(desc)
        world_models = {m['name'] for m in desc['models']}
    rospy.loginfo('car web view: %s (fixed frame %s%s)', web.url, fixed, ', world ' + world_file if world_file else '')
    print('car web view: %s' % web.url, flush=True)
    rospy.set_param('~url', web.url)

    buf = tf2_ros.Buffer(cache_time=rospy.Duration(10))
    tf2_ros.TransformListener(buf)
    cmd_pub = rospy.Publisher(rospy.get_param('~cmd_vel', 'cmd_vel'), Twist, queue_size=1)
    latest = {}
    lock = threading.Lock()

    def keep(key):
        def cb(msg):
            with lock:
                latest[key] = msg
        return cb

    # sensors: only while a browser looks; the cloud and the image sampled (see the module's note). TCP_NODELAY:
    # the subscriber asks for it and the publisher (sim_node) sets it on its socket, so the tail of a big message
    # is not held back by Nagle's algorithm waiting for an ACK
    sensors = {
        'scan': Sampled(rospy.get_param('~scan_topic', '/scan'), LaserScan, 0.0, tcp_nodelay=True),
        'cloud': Sampled(rospy.get_param('~cloud_topic', '/camera/depth/points'), PointCloud2,
                         1.0 / float(rospy.get_param('~cloud_rate', 2.0)), buff_size=2 ** 25, tcp_nodelay=True),
        'image': Sampled(rospy.get_param('~image_topic', '/camera/rgb/image_raw'), Image,
                         1.0 / float(rospy.get_param('~image_rate', 5.0)), buff_size=2 ** 24, tcp_nodelay=True),
    }
    rospy.Subscriber('/clock', Clock, keep('clock'), queue_size=1)
    from gazebo_msgs.msg import ModelStates
    rospy.Subscriber('/gazebo/model_states', ModelStates, keep('states'), queue_size=1)

    def service(name):
        def call(*_):
            try:
                rospy.ServiceProxy(name, Empty)()
            except (rospy.ServiceException, rospy.ROSException) as e:
                rospy.logwarn('web_view: %s: %s', name, e)
        return call

    web.on_pause = lambda p: service('/gazebo/pause_physics' if p else '/gazebo/unpause_physics')()
    web.on_reset = service('/gazebo/reset_world')

    def publish(_robot, v, w):
        t = Twist()
        t.linear.x, t.angular.z = v, w
        cmd_pub.publish(t)
    web.on_cmd = publish

    robots = [r for r in str(rospy.get_param('~robots', '')).split(',') if r]
    robot, links = None, []
    last_clock = None
    wall = time.monotonic()
    period = 1.0 / rate
    while not rospy.is_shutdown():
        t0 = time.monotonic()
        with lock:
            msgs = dict(latest)
            latest.clear()
        looking = web.has_clients()
        for key, sampled in sensors.items():
            m = sampled.poll(looking)
            if m is not None:
                msgs[key] = m
        if robot is None:
            states = msgs.get('states')
            name = robots[0] if robots else next((n for n in (states.name if states else []) if n not in world_models),
                                                 None)
            if name and rospy.has_param('robot_description'):
                text = rospy.get_param('robot_description')
                web.add_robot(name, text)
                links = [l['name'] for l in _core.load_urdf_string(text, name)['links']]
                robot = name
                rospy.loginfo('web_view: drawing robot %s (%d links)', name, len(links))
        for r, v, w in web.commands():
            publish(r, v, w)
        if robot is not None:
            base = None
            for link in links:
                try:
                    T = _T(buf.lookup_transform(fixed, link, rospy.Time(0)))
                except (tf2_ros.LookupException, tf2_ros.ConnectivityException, tf2_ros.ExtrapolationException):
                    continue
                web.set_link_pose(robot, link, T)
                base = T if base is None else base
            if base is not None:
                web.add_trail_point(robot, base[:2, 3])
        states = msgs.get('states')
        if states:
            for i, n in enumerate(states.name):
                if n in world_models:
                    p = states.pose[i]
                    from car.web_view import _rot
                    T = np.eye(4)
                    T[:3, :3] = _rot(p.orientation.x, p.orientation.y, p.orientation.z, p.orientation.w)
                    T[:3, 3] = (p.position.x, p.position.y, p.position.z)
                    web.set_model_pose(n, T)
        scan = msgs.get('scan')
        if scan is not None and robot is not None:
            try:
                T = _T(buf.lookup_transform(fixed, scan.header.frame_id, rospy.Time(0)))
                r = np.asarray(scan.ranges, dtype=np.float64)
                a = scan.angle_min + scan.angle_increment * np.arange(len(r))
                ok = np.isfinite(r) & (r >= scan.range_min) & (r <= scan.range_max)
                p = np.stack([r[ok] * np.cos(a[ok]), r[ok] * np.sin(a[ok]), np.zeros(ok.sum()), np.ones(ok.sum())])
                web.set_scan(robot, (T @ p)[:3].T)
            except (tf2_ros.LookupException, tf2_ros.ConnectivityException, tf2_ros.ExtrapolationException):
                pass
        cloud = msgs.get('cloud')
        if cloud is not None and robot is not None:
            try:
                T = _T(buf.lookup_transform(fixed, cloud.header.frame_id, rospy.Time(0)))
                xyz, rgb = cloud_xyz_rgb(cloud)
                keep_idx = np.isfinite(xyz).all(axis=1)
                xyz = xyz[keep_idx]
                rgb = rgb[keep_idx] if rgb is not None else None
                world = (T[:3, :3] @ xyz.T.astype(np.float64)).T + T[:3, 3]
                web.set_cloud(robot, world, rgb)
            except (tf2_ros.LookupException, tf2_ros.ConnectivityException, tf2_ros.ExtrapolationException):
                pass
        image = msgs.get('image')
        if image is not None:
            rgb = image_rgb(image)
            if rgb is not None:
                web.set_image(rgb)
        clock = msgs.get('clock')
        if clock is not None:
            now, sim = time.monotonic(), clock.clock.to_sec()
            rtf = None
            if last_clock is not None and now > last_clock[0]:
                rtf = (sim - last_clock[1]) / (now - last_clock[0])
            if last_clock is None or now - last_clock[0] > 1.0:
                last_clock = (now, sim)
            web.set_status(sim, rtf)
        # wall-clock pacing: this is a viewer, not part of the simulation
        time.sleep(max(0.0, period - (time.monotonic() - t0)))
    web.stop()
    return 0


if __name__ == '__main__':
    sys.exit(main())
