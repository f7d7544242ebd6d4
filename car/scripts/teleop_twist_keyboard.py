#!/usr/bin/env python3
"""teleop_twist_keyboard.py: keyboard teleop publishing geometry_msgs/Twist on cmd_vel."""
import sys

from car.ros.teleop import main

if __name__ == '__main__':
    sys.exit(main())
