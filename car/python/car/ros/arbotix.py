"""arbotix_driver for rviz-only simulation: arbotix_python's diff_controller in sim mode, per docs/TOOLS.md.

Reads ~controllers/<name>/ (type diff_controller, base_width and ticks_meter required, base_frame_id, odom_frame_id,
rate, Kp Kd Ki Ko accel_limit) and ~sim. cmd_vel sets the base velocity; the pose is integrated with Euler steps
at `rate`; odom and TF odom -> base_frame_id go out. Improvements over upstream: accel_limit [m/s^2] limits each
wheel's surface speed, and the model's wheel joints (from robot_description) turn at v / r.
"""
from __future__ import annotations

import math
import sys
from dataclasses import dataclass, field

NUMERIC_KEYS = ('base_width', 'ticks_meter', 'Kp', 'Kd', 'Ki', 'Ko', 'accel_limit', 'rate')


class ConfigError(Exception):
    """A configuration problem; str() names the parameter."""


@dataclass
class DiffConfig:
    name: str
    base_width: float              # [m] distance between the wheels
    ticks_meter: float             # [ticks/m] accepted (encoders are not simulated)
    base_frame_id: str = 'base_link'
    odom_frame_id: str = 'odom'
    rate: float = 10.0             # [Hz]
    accel_limit: float = 0.0       # [m/s^2] of each wheel's surface speed; 0 = unlimited
    gains: dict = field(default_factory=dict)  # Kp Kd Ki Ko: accepted, unused in simulation


def _number(params: dict, key: str, where: str, required: bool, default=None) -> float:
    if key not in params:
        if required:
            raise ConfigError('%s/%s is required (the distance between the wheels [m])' % (where, key)
                              if key == 'base_width' else '%s/%s is required' % (where, key))
        return default
    value = params[key]
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise ConfigError('%s/%s must be a number, got %r' % (where, key, value))
    return float(value)


def parse_controllers(controllers, prefix: str = '~controllers') -> list:
    """The diff controllers of an arbotix `controllers` parameter. Raises ConfigError naming the key."""
    if not isinstance(controllers, dict) or not controllers:
        raise ConfigError('%s must be a map of controllers (load config/control.yaml under the node)' % prefix)
    out = []
    for name, params in controllers.items():
        where = '%s/%s' % (prefix, name)
        if not isinstance(params, dict):
            raise ConfigError('%s must be a map, got %r' % (where, params))
        ctype = params.get('type')
        if ctype != 'diff_controller':
            raise ConfigError('%s/type: unknown controller type %r (car simulates diff_controller)' % (where, ctype))
        cfg = DiffConfig(name=name,
                         base_width=_number(params, 'base_width', where, True),
                         ticks_meter=_number(params, 'ticks_meter', where, True))
        if cfg.base_width <= 0:
            raise ConfigError('%s/base_width must be > 0, got %g' % (where, cfg.base_width))
        if cfg.ticks_meter <= 0:
            raise ConfigError('%s/ticks_meter must be > 0, got %g' % (where, cfg.ticks_meter))
        cfg.rate = _number(params, 'rate', where, False, 10.0)
        if cfg.rate <= 0:
            raise ConfigError('%s/rate must be > 0, got %g' % (where, cfg.rate))
        cfg.accel_limit = _number(params, 'accel_limit', where, False, 0.0)
        if cfg.accel_limit < 0:
            raise ConfigError('%s/accel_limit must be >= 0, got %g' % (where, cfg.accel_limit))
        for k in ('Kp', 'Kd', 'Ki', 'Ko'):
            v = _number(params, k, where, False)
            if v is not None:
                cfg.gains[k] = v
        for k in ('base_frame_id', 'odom_frame_id'):
            if k in params:
                if not isinstance(params[k], str) or not params[k]:
                    raise ConfigError('%s/%s must be a frame name, got %r' % (where, k, params[k]))
                setattr(cfg, k, params[k].lstrip('/'))
        out.append(cfg)
    return out


@dataclass
class Wheel:
    joint: str
    radius: float  # [m]
    side: int      # +1 left, -1 right


def find_wheels(model: dict) -> list:
    """Continuous joints whose child is a wheel (a cylinder turning about its own axis), left or right by the
    side of the robot they sit on. model: car._core.load_urdf_string's dict."""
    import numpy as np
    links = {l['name']: l for l in model['links']}
    wheels = []
    for j in model['joints']:
        if j['type'] != 'continuous':
            continue
        child = links[j['child']]
        cyl = [s for s in child['collisions'] + [v['shape'] for v in child['visuals']] if s['type'] == 'cylinder']
        if not cyl:
            continue
        axis = np.array(cyl[0]['origin']['rotation']) @ np.array([0.0, 0.0, 1.0])
        if abs(float(np.dot(axis, j['axis']))) < 0.99:
            continue
        y = links[j['child']]['pose_in_root']['xyz'][1]
        if abs(y) < 1e-9:
            continue
        # rolling forward (+x) is a positive turn about +y, on either side: v = w_y r
        direction = 1 if j['axis'][1] > 0 else -1
        wheels.append((Wheel(j['name'], cyl[0]['radius'], 1 if y > 0 else -1), direction))
    return wheels


class DiffSim:
    """The kinematic base: velocities from cmd_vel, per-wheel acceleration limit, Euler integration."""

    def __init__(self, cfg: DiffConfig):
        self.cfg = cfg
        self.x = self.y = self.th = 0.0    # [m], [m], [rad] odom frame
        self.target = (0.0, 0.0)           # (left, right) wheel surface speeds [m/s] commanded
        self.wheel = [0.0, 0.0]            # (left, right) wheel surface speeds [m/s] now

    def command(self, v: float, w: float) -> None:
        half = self.cfg.base_width / 2.0
        self.target = (v - w * half, v + w * half)

    @property
    def v(self) -> float:
        return (self.wheel[0] + self.wheel[1]) / 2.0

    @property
    def w(self) -> float:
        return (self.wheel[1] - self.wheel[0]) / self.cfg.base_width

    def step(self, dt: float) -> None:
        limit = self.cfg.accel_limit * dt
        for i in (0, 1):
            d = self.target[i] - self.wheel[i]
            if limit > 0:
                d = max(-limit, min(limit, d))
            self.wheel[i] += d
        v, w = self.v, self.w
        self.x += math.cos(self.th) * v * dt
        self.y += math.sin(self.th) * v * dt
        self.th += w * dt


def main(argv=None) -> int:
    import rospy
    import tf2_ros
    from geometry_msgs.msg import TransformStamped, Twist
    from nav_msgs.msg import Odometry
    from sensor_msgs.msg import JointState

    rospy.init_node('arbotix', argv=argv)
    if not rospy.get_param('~sim', False):
        rospy.logfatal('arbotix_driver: ~sim must be true: car simulates the base, it drives no hardware')
        return 1
    try:
        configs = parse_controllers(rospy.get_param('~controllers', None))
    except ConfigError as e:
        rospy.logfatal('arbotix_driver: %s', e)
        return 1
    if len(configs) != 1:
        rospy.logfatal('arbotix_driver: one diff_controller expected, found %d', len(configs))
        return 1
    cfg = configs[0]
    sim = DiffSim(cfg)

    wheels = []
    if rospy.has_param('robot_description'):
        from car import _core
        try:
            model = _core.load_urdf_string(rospy.get_param('robot_description'), 'robot_description', False)
            wheels = find_wheels(model)
        except ValueError as e:
            rospy.logwarn('arbotix_driver: robot_description: %s; wheels will not turn', e)
    positions = {w.joint: 0.0 for w, _ in wheels}
    rospy.loginfo('arbotix_driver: %s: diff_controller, base_width %g m, %s -> %s at %g Hz, accel_limit %g m/s^2, '
                  'wheels: %s', cfg.name, cfg.base_width, cfg.odom_frame_id, cfg.base_frame_id, cfg.rate,
                  cfg.accel_limit, ', '.join('%s (r %g m, %s)' % (w.joint, w.radius, 'left' if w.side > 0 else 'right')
                                             for w, _ in wheels) or 'none found')

    def on_cmd(msg):
        if not (math.isfinite(msg.linear.x) and math.isfinite(msg.angular.z)):
            rospy.logwarn_throttle(1.0, 'arbotix_driver: ignored a cmd_vel with a non-finite value')
            return
        sim.command(msg.linear.x, msg.angular.z)

    rospy.Subscriber('cmd_vel', Twist, on_cmd, queue_size=5)
    odom_pub = rospy.Publisher('odom', Odometry, queue_size=5)
    js_pub = rospy.Publisher('joint_states', JointState, queue_size=5)
    tf = tf2_ros.TransformBroadcaster()
    rate = rospy.Rate(cfg.rate)
    then = rospy.Time.now()
    while not rospy.is_shutdown():
        try:
            rate.sleep()
        except rospy.ROSInterruptException:
            break
        except rospy.ROSTimeMovedBackwardsException:
            then = rospy.Time.now()
            continue
        now = rospy.Time.now()
        dt = (now - then).to_sec()
        then = now
        if dt <= 0:
            continue
        sim.step(dt)
        for w, direction in wheels:
            speed = sim.wheel[0] if w.side > 0 else sim.wheel[1]
            positions[w.joint] += direction * speed / w.radius * dt
        q = (0.0, 0.0, math.sin(sim.th / 2), math.cos(sim.th / 2))
        t = TransformStamped()
        t.header.stamp = now
        t.header.frame_id = cfg.odom_frame_id
        t.child_frame_id = cfg.base_frame_id
        t.transform.translation.x, t.transform.translation.y = sim.x, sim.y
        (t.transform.rotation.x, t.transform.rotation.y, t.transform.rotation.z, t.transform.rotation.w) = q
        tf.sendTransform(t)
        o = Odometry()
        o.header = t.header
        o.child_frame_id = cfg.base_frame_id
        o.pose.pose.position.x, o.pose.pose.position.y = sim.x, sim.y
        (o.pose.pose.orientation.x, o.pose.pose.orientation.y, o.pose.pose.orientation.z,
         o.pose.pose.orientation.w) = q
        o.twist.twist.linear.x, o.twist.twist.angular.z = sim.v, sim.w
        odom_pub.publish(o)
        if wheels:
            js = JointState()
            js.header.stamp = now
            for w, direction in wheels:
                js.name.append(w.joint)
                js.position.append(positions[w.joint])
                speed = sim.wheel[0] if w.side > 0 else sim.wheel[1]
                js.velocity.append(direction * speed / w.radius)
            js_pub.publish(js)
    return 0


if __name__ == '__main__':
    sys.exit(main())
