"""The world in rviz: the visual geometry of an SDF world as a latched visualization_msgs/MarkerArray, coloured
by material, following the models that move while the simulator runs (/gazebo/model_states)."""
from __future__ import annotations

import os
import sys
import threading

import numpy as np

from car import materials
from car.world_geometry import model_transform, shapes, transform

PLANE_THICKNESS = 0.001  # [m] planes are drawn as thin boxes, their top face at the plane


def _quat(R: np.ndarray):
    """(x, y, z, w) of a rotation matrix."""
    w = np.sqrt(max(0.0, 1.0 + R[0, 0] + R[1, 1] + R[2, 2])) / 2.0
    x = np.sqrt(max(0.0, 1.0 + R[0, 0] - R[1, 1] - R[2, 2])) / 2.0
    y = np.sqrt(max(0.0, 1.0 - R[0, 0] + R[1, 1] - R[2, 2])) / 2.0
    z = np.sqrt(max(0.0, 1.0 - R[0, 0] - R[1, 1] + R[2, 2])) / 2.0
    x = np.copysign(x, R[2, 1] - R[1, 2])
    y = np.copysign(y, R[0, 2] - R[2, 0])
    z = np.copysign(z, R[1, 0] - R[0, 1])
    return float(x), float(y), float(z), float(w)


def marker_specs(desc: dict) -> list:
    """One plain dict per visual: ns (model), id, type, pose (4x4), scale, rgba, mesh; and where it sits on
    its model, so a moving model can move its markers."""
    out = []
    for m, l, s, T in shapes(desc, 'visuals'):
        spec = {'ns': m['name'], 'id': len(out), 'rgba': materials.visual_colour(s), 'mesh': '',
                'in_model': np.linalg.inv(model_transform(m)) @ T, 'static': m['static']}
        t = s['type']
        if t == 'box':
            spec.update(type='cube', scale=list(s['size']))
        elif t == 'cylinder':
            spec.update(type='cylinder', scale=[2 * s['radius'], 2 * s['radius'], s['length']])
        elif t == 'sphere':
            spec.update(type='sphere', scale=[2 * s['radius']] * 3)
        elif t == 'plane':
            n = np.array(s['normal'])
            # a thin box with its top face on the plane, turned so its z is the normal
            z = n / np.linalg.norm(n)
            x = np.cross([0, 1, 0], z) if abs(z[1]) < 0.9 else np.cross(z, [1, 0, 0])
            x /= np.linalg.norm(x)
            R = np.column_stack([x, np.cross(z, x), z])
            P = np.eye(4)
            P[:3, :3] = R
            P[:3, 3] = -z * PLANE_THICKNESS / 2
            T = T @ P
            spec['in_model'] = spec['in_model'] @ P
            spec.update(type='cube', scale=[s.get('size', [100, 100])[0] or 100,
                                            s.get('size', [100, 100])[1] or 100, PLANE_THICKNESS])
        elif t == 'mesh':
            uri = s['uri']
            if not uri.startswith('package://'):
                from car import _core
                path = _core.resolve_uri(uri, os.path.dirname(desc['source']))
                uri = 'file://' + os.path.abspath(path) if path else uri
            spec.update(type='mesh', scale=list(s['scale']), mesh=uri)
        else:
            continue
        spec['pose'] = T
        out.append(spec)
    return out


def to_marker_array(specs: list, frame_id: str, stamp=None):
    from visualization_msgs.msg import Marker, MarkerArray
    types = {'cube': Marker.CUBE, 'cylinder': Marker.CYLINDER, 'sphere': Marker.SPHERE, 'mesh': Marker.MESH_RESOURCE}
    arr = MarkerArray()
    for s in specs:
        mk = Marker()
        mk.header.frame_id = frame_id
        if stamp is not None:
            mk.header.stamp = stamp
        mk.ns, mk.id, mk.type, mk.action = s['ns'], s['id'], types[s['type']], Marker.ADD
        T = s['pose']
        mk.pose.position.x, mk.pose.position.y, mk.pose.position.z = (float(v) for v in T[:3, 3])
        (mk.pose.orientation.x, mk.pose.orientation.y, mk.pose.orientation.z,
         mk.pose.orientation.w) = _quat(T[:3, :3])
        mk.scale.x, mk.scale.y, mk.scale.z = (float(v) for v in s['scale'])
        mk.color.r, mk.color.g, mk.color.b, mk.color.a = (float(v) for v in s['rgba'])
        if s['mesh']:
            mk.mesh_resource = s['mesh']
            mk.mesh_use_embedded_materials = True
        mk.frame_locked = True
        arr.markers.append(mk)
    return arr


def main(argv=None) -> int:
    import rospy
    from visualization_msgs.msg import MarkerArray

    rospy.init_node('world_markers', argv=argv)
    path = rospy.get_param('~world', '')
    frame = rospy.get_param('~frame_id', 'odom')
    follow = rospy.get_param('~follow', True)
    # [Hz] of wall time: how often moved models are looked for while someone subscribes
    rate = rospy.get_param('~rate', 10.0)
    try:
        ok = float(rate) > 0
    except (TypeError, ValueError):
        ok = False
    if not ok:
        rospy.logfatal('world_markers: ~rate must be > 0 [Hz of wall time], got %s', rate)
        return 1
    rate = float(rate)
    from car import _core
    try:
        desc = _core.load_world_file(path)
    except (ValueError, RuntimeError) as e:
        rospy.logfatal('world_markers: %s', e)
        return 1
    specs = marker_specs(desc)
    follower = _Follower() if follow else None
    pub = rospy.Publisher('world_markers', MarkerArray, queue_size=1, latch=True,
                          subscriber_listener=follower.listener() if follower else None)
    pub.publish(to_marker_array(specs, frame))
    rospy.loginfo('world_markers: %s: %d markers of %d models in frame %s%s', path, len(specs), len(desc['models']),
                  frame, ', following moving models while someone subscribes' if follow else '')
    # the markers carry no stamp (rviz draws them at the latest transform) and the loop below keeps wall time, as
    # rviz draws: no sim time to read
    from car.ros.rosclock import stop_clock
    stop_clock()
    if follow:
        # every model may move: a static one too, by set_model_state (docs/COMPAT.md)
        moving = {s['ns'] for s in specs}
        latest = {}
        from gazebo_msgs.msg import ModelStates
        last_sent = {}
        import time
        while not rospy.is_shutdown():
            # [s] of wall time between looks at the newest model_states
            time.sleep(1.0 / rate)
            raw = follower.take()
            if raw is not None:
                msg = ModelStates().deserialize(raw._buff)
                for name, pose in zip(msg.name, msg.pose):
                    if name in moving:
                        latest[name] = pose
            changed = False
            for name, p in list(latest.items()):
                key = (p.position.x, p.position.y, p.position.z, p.orientation.x, p.orientation.y, p.orientation.z,
                       p.orientation.w)
                if last_sent.get(name) == key:
                    continue
                last_sent[name] = key
                Tm = transform({'xyz': key[:3], 'rotation': _rot(key[3:])})
                for s in specs:
                    if s['ns'] == name:
                        s['pose'] = Tm @ s['in_model']
                changed = True
            if changed:
                pub.publish(to_marker_array(specs, frame))
    else:
        rospy.spin()
    return 0


class _Follower:
    """/gazebo/model_states, subscribed only while /world_markers has a subscriber: nobody looking (a headless run,
    a benchmark), the simulator neither builds nor sends model_states for this node (100 Hz of sim time), as a
    gazebo_ros sensor stays off without subscribers. model_states comes at 100 Hz and the markers follow at `rate`:
    the newest message's bytes are kept (rospy.AnyMsg) and only the one a tick uses is unpacked."""

    def __init__(self):
        self.lock = threading.Lock()
        self.sub = None
        self.newest = None

    def _on_states(self, raw):
        self.newest = raw

    def take(self):
        raw, self.newest = self.newest, None
        return raw

    def listener(self):
        import rospy
        follower = self

        class Listener(rospy.SubscribeListener):
            def peer_subscribe(self, topic_name, topic_publish, peer_publish):
                with follower.lock:
                    if follower.sub is None:
                        follower.sub = rospy.Subscriber('/gazebo/model_states', rospy.AnyMsg, follower._on_states,
                                                        queue_size=1)
                        rospy.loginfo('world_markers: %s has a subscriber: following /gazebo/model_states',
                                      topic_name)

            def peer_unsubscribe(self, topic_name, num_peers):
                with follower.lock:
                    if num_peers == 0 and follower.sub is not None:
                        follower.sub.unregister()
                        follower.sub = None
                        rospy.loginfo('world_markers: %s has no subscriber: /gazebo/model_states left', topic_name)

        return Listener()


def _rot(q):
    x, y, z, w = q
    return [[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
            [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
            [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]]


if __name__ == '__main__':
    sys.exit(main())
