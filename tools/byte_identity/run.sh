#!/bin/bash
# Usage: run.sh WORKSPACE SCENARIO PORT: one recording with WORKSPACE's sim_node, paused start, the command sent
# while paused, rtf 1; prints count and sha256 per topic. Exits 1, naming what it waited for, when a wait runs out.
#   rover      the ros_control rover (diff_drive_controller), 3 s: odom, joint_states, tf
#   arm        the ros_control arm (a follow_joint_trajectory goal), 3 s: joint_states, controller state, result
#   sensors    sensor_bot.xacro (laser, depth camera, IMU with noise) driving in box_house, 2 s: every sensor topic
#   box_house  the tutorial's seed car (car_camera_lidar02.xacro) driving in box_house, 3 s: odom, tf, scan
#   plugins    plugin_frames' box under a tf_prefix (p3d, planar_move, range, block laser, bumper, camera) and
#              ray_sensors' cube (sonars, velodyne, stereo multicamera), 2 s: every one of their topics
# /tf counts from 1 s (TOPIC@FROM): sim_node advertises it on its first message, so the recorder joins late.
# Run it with two builds and compare (docs/ARCHITECTURE.md, "Byte identity").
ws=$1; sc=$2; port=$3; here=$(cd $(dirname $0) && pwd)
case $sc in
  rover) T=3.0; topics="/rover_velocity_controller/odom /joint_states /tf@1" ;;
  arm) T=3.0; topics="/arm/joint_states /arm/arm_controller/state /arm/arm_controller/follow_joint_trajectory/result" ;;
  sensors) T=2.0; topics="/scan /imu /camera/rgb/image_raw /camera/rgb/camera_info /camera/depth/image_raw
                          /camera/depth/camera_info /camera/depth/points" ;;
  box_house) T=3.0; topics="/odom /tf@1 /scan" ;;
  plugins) T=2.0; topics="/r1/truth /r1/odom /r1/scan /r1/sonar /r1/block /r1/bumper /r1/cam/camera_info /sonar
                          /sonar_slow /velodyne_points /stereo/left/camera_info /stereo/right/image_raw /tf@1" ;;
  *) echo "run.sh: unknown scenario '$sc' (rover, arm, sensors, box_house or plugins)" >&2; exit 2 ;;
esac
source $ws/devel/setup.bash
export ROS_MASTER_URI=http://localhost:$port
# roscore and roslaunch each lead a process group of their own, ended by its id at the end
setsid roscore -p $port > /tmp/bc_core_$port.log 2>&1 &
core=$!
stop() {
  kill -INT -- -$launch 2>/dev/null
  for i in $(seq 50); do kill -0 -- -$launch 2>/dev/null || break; sleep 0.1; done
  kill -KILL -- -$launch 2>/dev/null
  kill -INT -- -$core 2>/dev/null
  for i in $(seq 50); do kill -0 -- -$core 2>/dev/null || break; sleep 0.1; done
  kill -KILL -- -$core 2>/dev/null
}
# wait_for WHAT LIMIT COMMAND...: polls COMMAND until it succeeds; after LIMIT seconds fails naming WHAT
wait_for() {
  local what=$1 limit=$2; shift 2
  local end=$((SECONDS + limit))
  until "$@" >/dev/null 2>&1; do
    if [ $SECONDS -ge $end ]; then
      echo "run.sh $sc: timed out after ${limit} s waiting for $what (logs: /tmp/bc_core_$port.log, /tmp/bc_launch_$port.log)" >&2
      stop; exit 1
    fi
    sleep 0.2
  done
}
launch=$core
wait_for "the master on port $port" 30 rosparam get /run_id
setsid roslaunch -p $port $here/$sc.launch > /tmp/bc_launch_$port.log 2>&1 &
launch=$!
wait_for "the launch's parameters (/use_sim_time)" 60 rosparam get /use_sim_time
timeout 400 /usr/bin/python3 $here/record.py $sc $T $topics __name:=bytecheck
rc=$?
[ $rc = 124 ] && echo "run.sh $sc: the recorder ran past 400 s" >&2
stop
exit $rc
