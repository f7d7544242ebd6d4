"""car's ROS side in Python: the nodes and clients that talk to a ROS master (rospy, ROS messages): spawn_model
(spawn), gzserver's command line (gzserver), controller_manager's spawner (control), arbotix_driver (arbotix),
teleop_twist_keyboard (teleop), static_transform_publisher (static_tf), world_markers, the web view's node
(web_view_node), world_tool map --publish (map_publisher) and their /clock helper (rosclock). The tools that need
no master stay in car itself; nothing there imports this package, except world_tool map --publish when asked.
pip's wheel (no ROS) does not ship it. Importing it imports no rospy: each module imports rospy where it talks to
ROS, so its other parts (argument parsing, kinematics) are tested without a master."""
