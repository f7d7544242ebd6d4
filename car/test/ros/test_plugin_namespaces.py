#!/usr/bin/env python3
"""rostest: the simulator advertises each plug-in's topics under the namespace its file's rule gives
(docs/COMPAT-plugins.md "Namespaces"); the model is spawned with robot_namespace '' so nothing is injected."""
import time
import unittest

import rospy
import rostest
from gazebo_msgs.srv import SpawnModel
from geometry_msgs.msg import Pose

# Model "nsbot": range with an empty <robotNamespace> (read directly: global), laser with an empty one
# (GetRobotNamespace: the model name), imu_sensor with none (LoadParameters: "/" + model + "/"),
# joint_state_publisher with "/" (GazeboRos rule, "/" is global), p3d with "r2" (as written).
URDF = """<robot name="nsbot">
  <link name="base"><inertial><mass value="1"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/>
    </inertial><collision><geometry><box size="0.2 0.2 0.1"/></geometry></collision></link>
  <link name="wheel"><inertial><mass value="0.1"/><inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.001"/>
    </inertial></link>
  <joint name="wheel_joint" type="continuous"><parent link="base"/><child link="wheel"/><axis xyz="0 1 0"/></joint>
  <gazebo><plugin name="p3d" filename="libgazebo_ros_p3d.so"><robotNamespace>r2</robotNamespace>
    <bodyName>base</bodyName><topicName>ground_truth</topicName></plugin></gazebo>
  <gazebo><plugin name="jsp" filename="libgazebo_ros_joint_state_publisher.so"><robotNamespace>/</robotNamespace>
    <jointName>wheel_joint</jointName></plugin></gazebo>
  <gazebo reference="base">
    <sensor type="ray" name="sonar"><ray><scan><horizontal><samples>3</samples><min_angle>-0.1</min_angle>
      <max_angle>0.1</max_angle></horizontal></scan><range><min>0.05</min><max>2</max></range></ray>
      <plugin name="range" filename="libgazebo_ros_range.so"><robotNamespace></robotNamespace>
      <topicName>sonar</topicName></plugin></sensor>
    <sensor type="ray" name="lidar"><ray><scan><horizontal><samples>3</samples><min_angle>-0.1</min_angle>
      <max_angle>0.1</max_angle></horizontal></scan><range><min>0.05</min><max>2</max></range></ray>
      <plugin name="laser" filename="libgazebo_ros_laser.so"><robotNamespace></robotNamespace>
      <topicName>scan</topicName></plugin></sensor>
    <sensor type="imu" name="imu"><plugin name="imu" filename="libgazebo_ros_imu_sensor.so">
      <topicName>imu</topicName><frameName>base</frameName></plugin></sensor>
  </gazebo>
</robot>"""


class PluginNamespaces(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_plugin_namespaces')
        rospy.wait_for_service('/gazebo/spawn_urdf_model', 60.0)
        pose = Pose()
        pose.position.z = 0.1
        pose.orientation.w = 1.0
        res = rospy.ServiceProxy('/gazebo/spawn_urdf_model', SpawnModel)('nsbot', URDF, '', pose, '')
        assert res.success, res.status_message
        # the adapters advertise while the spawn call runs; wait (wall time) for the last one the master lists
        deadline = time.time() + 30.0
        while time.time() < deadline and '/nsbot/imu' not in cls.topics():
            time.sleep(0.1)

    @staticmethod
    def topics():
        return dict(rospy.get_published_topics())

    def test_range_empty_is_global(self):
        self.assertIn('/sonar', self.topics())
        self.assertNotIn('/nsbot/sonar', self.topics())

    def test_laser_empty_is_the_model_name(self):
        self.assertIn('/nsbot/scan', self.topics())
        self.assertNotIn('/scan', self.topics())

    def test_imu_sensor_absent_is_the_model_name(self):
        self.assertIn('/nsbot/imu', self.topics())
        self.assertNotIn('/imu', self.topics())

    def test_joint_state_publisher_slash_is_global(self):
        self.assertIn('/joint_states', self.topics())
        self.assertNotIn('/nsbot/joint_states', self.topics())

    def test_p3d_explicit_is_kept(self):
        self.assertIn('/r2/ground_truth', self.topics())


if __name__ == '__main__':
    rostest.rosrun('car', 'plugin_namespaces', PluginNamespaces)
