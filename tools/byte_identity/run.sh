#!/bin/bash
# Usage: run.sh WORKSPACE SCENARIO PORT (SCENARIO rover or arm): one recording of the ros_control fixtures with
# WORKSPACE's sim_node, paused start, commands sent while paused, rtf 1; prints count and sha256 per topic.
# Run it with two builds and compare (docs/ARCHITECTURE.md, "Byte identity").
ws=$1; sc=$2; port=$3; here=$(cd $(dirname $0) && pwd)
source $ws/devel/setup.bash
export ROS_MASTER_URI=http://localhost:$port
roscore -p $port > /tmp/bc_core_$port.log 2>&1 &
core=$!
sleep 3
roslaunch -p $port $here/$sc.launch > /tmp/bc_launch_$port.log 2>&1 &
launch=$!
until rosparam get /use_sim_time >/dev/null 2>&1; do sleep 0.5; done
if [ $sc = rover ]; then topics="/rover_velocity_controller/odom /joint_states /tf"; else topics="/arm/joint_states /arm/arm_controller/state /arm/arm_controller/follow_joint_trajectory/result"; fi
timeout 120 /usr/bin/python3 $here/record.py $sc 3.0 $topics __name:=bytecheck
kill -INT $launch; sleep 3; kill -9 $launch 2>/dev/null; kill -INT $core; sleep 1; kill -9 $core 2>/dev/null
pkill -f "roslaunch -p $port" ; pkill -f "__master:=http://localhost:$port" ; true
