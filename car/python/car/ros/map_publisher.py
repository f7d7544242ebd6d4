"""world_tool map --publish: the occupancy grid world_tool map wrote, latched as nav_msgs/OccupancyGrid."""
from __future__ import annotations

import numpy as np


def to_occupancy_grid(grid: np.ndarray, origin, resolution: float, frame_id: str):
    """An OccupancyGrid of grid (rows from the origin [m], frame_id; cells of resolution [m])."""
    from nav_msgs.msg import OccupancyGrid
    msg = OccupancyGrid()
    msg.header.frame_id = frame_id
    msg.info.resolution = resolution
    msg.info.height, msg.info.width = grid.shape
    msg.info.origin.position.x, msg.info.origin.position.y = float(origin[0]), float(origin[1])
    msg.info.origin.orientation.w = 1.0
    msg.data = grid.ravel().tolist()  # row-major from the origin, as OccupancyGrid wants
    return msg


def publish(grid: np.ndarray, origin, resolution: float, frame_id: str, topic: str, world: str) -> None:
    """Latches the grid on topic as the node world_map, then spins until shut down."""
    import rospy
    from nav_msgs.msg import OccupancyGrid
    rospy.init_node('world_map', anonymous=True)
    pub = rospy.Publisher(topic, OccupancyGrid, queue_size=1, latch=True)
    msg = to_occupancy_grid(grid, origin, resolution, frame_id)
    msg.header.stamp = rospy.Time.now()
    pub.publish(msg)
    rospy.loginfo('world_map: %s latched on %s in frame %s', world, topic, frame_id)
    rospy.spin()
