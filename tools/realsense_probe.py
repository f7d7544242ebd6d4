#!/usr/bin/env python3
"""The D435's checks for tools/realsense.sh (run on /usr/bin/python3, sim time): PAL's realsense_gazebo_plugin built
unchanged publishes the four images and their camera_info under /camera, and the depth image sees a wall at its
distance. Prints one line per check: CHECK | FIGURE | ok/FAIL.

Figures by hand: the D435's sensors in _d435.gazebo.xacro: colour 640 x 480 RGB_INT8 (the plug-in's rgb8), infrared
1280 x 720 L_INT8 (its 8UC1), depth 1280 x 720, 16UC1 in mm (its DEPTH_SCALE_M 0.001). camera_info's fx is the
plug-in's (width / 2) / tan(hfov / 2): colour 69.4 deg: 320 / tan(34.7 deg) = 320 / 0.69243 = 462.14; depth and
infrared 85.2 deg: 640 / tan(42.6 deg) = 640 / 0.91955 = 695.99. The wall: a static box whose near face is the plane x = 1.5 m; the depth frame's origin
is camera_link's, 0.0125 m above and 0.0175 m left of the model frame, so the centre pixel reads 1.5 m less the
model's x (the camera level, facing +x). Its noise is the sensor's <noise> (stddev 0.1 m): the median of the
centre 11 x 11 pixels (121) has a spread of about 1.25 x 0.1 / 11 = 0.011 m, so +-0.045 m is 4 of them.
"""
import array
import math

import rospy
from gazebo_msgs.msg import ModelStates
from gazebo_msgs.srv import SpawnModel
from geometry_msgs.msg import Pose
from sensor_msgs.msg import CameraInfo, Image

import probe_util

WALL = """<?xml version="1.0"?><sdf version="1.6"><model name="wall"><static>true</static>
<link name="link"><collision name="c"><geometry><box><size>0.2 4 2</size></box></geometry></collision>
<visual name="v"><geometry><box><size>0.2 4 2</size></box></geometry></visual></link></model></sdf>"""

results = probe_util.Results()
check = results.check
images, infos = {}, {}
state = {"pose": None}


def wait_until(what, cond, sim_s, wall_s=300.0):
    return probe_util.wait_until("realsense_probe", what, cond, sim_s, wall_s)


def keep(store, key):
    def cb(m):
        store[key] = m
    return cb


def on_states(m):
    if "d435" in m.name:
        state["pose"] = m.pose[m.name.index("d435")]


def yaw_pitch_roll(q):
    yaw = math.atan2(2 * (q.w * q.z + q.x * q.y), 1 - 2 * (q.y * q.y + q.z * q.z))
    pitch = math.asin(max(-1.0, min(1.0, 2 * (q.w * q.y - q.z * q.x))))
    roll = math.atan2(2 * (q.w * q.x + q.y * q.z), 1 - 2 * (q.x * q.x + q.y * q.y))
    return yaw, pitch, roll


def main():
    rospy.init_node("realsense_probe")
    streams = {"color": ("rgb8", 640, 480, 462.14), "depth": ("16UC1", 1280, 720, 695.99),
               "infra1": ("8UC1", 1280, 720, 695.99), "infra2": ("8UC1", 1280, 720, 695.99)}
    for s in streams:
        rospy.Subscriber("/camera/%s/image_raw" % s, Image, keep(images, s))
        rospy.Subscriber("/camera/%s/camera_info" % s, CameraInfo, keep(infos, s))
    rospy.Subscriber("/gazebo/model_states", ModelStates, on_states)
    if not wait_until("an image on each of the four topics", lambda: len(images) == 4, 60.0):
        check("the four image topics publish", "only %s" % sorted(images), False)
        return
    for s, (enc, w, h, fx) in sorted(streams.items()):
        m, i = images[s], infos.get(s)
        check("/camera/%s/image_raw" % s, "%s %d x %d" % (m.encoding, m.width, m.height),
              (m.encoding, m.width, m.height) == (enc, w, h))
        check("/camera/%s/camera_info fx" % s, "%.2f (by hand %.2f)" % (i.K[0], fx) if i else "none",
              i is not None and abs(i.K[0] - fx) < 0.01)
    rospy.wait_for_service("/gazebo/spawn_sdf_model", 30)
    wall = Pose()
    wall.position.x, wall.position.z = 1.6, 1.0
    wall.orientation.w = 1.0
    rospy.ServiceProxy("/gazebo/spawn_sdf_model", SpawnModel)("wall", WALL, "", wall, "world")
    # the wall in the frames taken after 1 s of sim time
    t_wall = rospy.get_time() + 1.0
    wait_until("1 s of sim time after the wall", lambda: rospy.get_time() >= t_wall, 30.0)
    images.pop("depth", None)
    if not wait_until("a depth image with the wall", lambda: "depth" in images, 30.0):
        check("depth to the wall", "no depth image", False)
        return
    m, p = images["depth"], state["pose"]
    depth = array.array("H", m.data)
    centre = sorted(depth[r * m.width + c] for r in range(m.height // 2 - 5, m.height // 2 + 6)
                    for c in range(m.width // 2 - 5, m.width // 2 + 6))[60] / 1000.0
    yaw, pitch, roll = yaw_pitch_roll(p.orientation)
    expected = 1.5 - p.position.x
    level = max(abs(yaw), abs(pitch), abs(roll)) < 0.01
    check("depth at the centre to the wall (median of 11 x 11)",
          "%.3f m, by hand %.3f m (model x %.4f m, yaw/pitch/roll %.4f %.4f %.4f rad)"
          % (centre, expected, p.position.x, yaw, pitch, roll), level and abs(centre - expected) < 0.045)


if __name__ == "__main__":
    probe_util.run(main, results)
