#!/usr/bin/env python3
"""Physics steps/s at 1 kHz for the seed car in box_house: car's core (C++ and Python API), car's ROS node,
and PyBullet (from PyPI) stepping the same expanded URDF and world, all measured in this run.

usage: bench_physics.py [--seconds S]   (run through bench/run.sh, which sets up the environment)
"""
import argparse
import math
import os
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
URDF = os.path.join(ROOT, 'test', 'data', 'car_camera_lidar04.urdf')
WORLD = os.path.join(ROOT, 'worlds', 'box_house.world')
SETTLE = 3000  # steps before timing: resting world objects may fall asleep in either engine


def core_python(steps):
    from car import _core
    w = _core.World(WORLD)
    with open(URDF) as f:
        w.spawn_urdf(f.read(), 'mycar')
    w.set_cmd_vel('mycar', 1.0, 1.0)
    w.step(SETTLE)
    t = time.perf_counter()
    w.step(steps)
    return steps / (time.perf_counter() - t)


def core_cpp(steps):
    exe = os.path.join(ROOT, '.ws', 'devel', 'lib', 'car', 'bench_core')
    out = subprocess.run([exe, URDF, WORLD, str(steps)], capture_output=True, text=True, check=True).stdout
    return float(out.split()[1])


def pybullet_world(p, iterations):
    """box_house built in PyBullet from the description car reads (PyBullet's own loadSDF crashes on it)."""
    from car import _core
    desc = _core.load_world_file(WORLD)
    p.setGravity(*desc['gravity'])
    p.setTimeStep(desc['step_size'])
    if iterations:
        p.setPhysicsEngineParameter(numSolverIterations=iterations)

    def quat(rot):
        import numpy as np
        from scipy.spatial.transform import Rotation
        return Rotation.from_matrix(np.array(rot)).as_quat().tolist()

    for m in desc['models']:
        for l in m['links']:
            for c in l['collisions']:
                pos = [a + b for a, b in zip(l['world_pose']['xyz'], [0, 0, 0])]
                # collision pose in the world: link world pose * collision origin
                import numpy as np
                R = np.array(l['world_pose']['rotation'])
                cpos = (np.array(l['world_pose']['xyz']) + R @ np.array(c['origin']['xyz'])).tolist()
                crot = (R @ np.array(c['origin']['rotation'])).tolist()
                if c['type'] == 'plane':
                    shape = p.createCollisionShape(p.GEOM_PLANE, planeNormal=c['normal'])
                elif c['type'] == 'box':
                    shape = p.createCollisionShape(p.GEOM_BOX, halfExtents=[s / 2 for s in c['size']])
                elif c['type'] == 'cylinder':
                    shape = p.createCollisionShape(p.GEOM_CYLINDER, radius=c['radius'], height=c['length'])
                elif c['type'] == 'sphere':
                    shape = p.createCollisionShape(p.GEOM_SPHERE, radius=c['radius'])
                else:
                    continue
                mass = 0.0 if m['static'] or not l['inertial'] else l['inertial']['mass']
                body = p.createMultiBody(mass, shape, basePosition=cpos, baseOrientation=quat(crot))
                p.changeDynamics(body, -1, lateralFriction=c['mu'])


def pybullet_steps(steps, iterations=None):
    import pybullet as p
    p.connect(p.DIRECT)
    pybullet_world(p, iterations)
    car = p.loadURDF(URDF, [0, 0, 0])
    joints = {p.getJointInfo(car, i)[1].decode(): i for i in range(p.getNumJoints(car))}
    for j in joints.values():
        p.setJointMotorControl2(car, j, p.VELOCITY_CONTROL, targetVelocity=0, force=0)
    r, sep = 0.0325, 0.2
    p.setJointMotorControl2(car, joints['left2link'], p.VELOCITY_CONTROL, targetVelocity=(1 - sep / 2) / r, force=30)
    p.setJointMotorControl2(car, joints['right2link'], p.VELOCITY_CONTROL, targetVelocity=(1 + sep / 2) / r, force=30)
    for _ in range(SETTLE):
        p.stepSimulation()
    t = time.perf_counter()
    for _ in range(steps):
        p.stepSimulation()
    rate = steps / (time.perf_counter() - t)
    p.disconnect()
    return rate


def ros_node(seconds):
    """sim.launch at rtf 0, no subscribers but the measuring one: sim seconds per wall second."""
    env = dict(os.environ, ROS_MASTER_URI='http://localhost:11399')
    launch = subprocess.Popen(['roslaunch', '-p', '11399', 'car', 'sim.launch', 'rtf:=0'], env=env,
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        os.environ['ROS_MASTER_URI'] = env['ROS_MASTER_URI']
        import rospy
        from rosgraph_msgs.msg import Clock
        from car.srv import GetModelState
        rospy.init_node('bench_physics', anonymous=True, disable_signals=True)
        rospy.wait_for_service('/gazebo/get_model_state', timeout=60)
        get = rospy.ServiceProxy('/gazebo/get_model_state', GetModelState)
        while not get('mycar', '').success:
            time.sleep(0.1)

        def sim_now():
            return rospy.wait_for_message('/clock', Clock, timeout=30).clock.to_sec()

        s0, w0 = sim_now(), time.perf_counter()
        time.sleep(seconds)
        s1, w1 = sim_now(), time.perf_counter()
        return (s1 - s0) / 0.001 / (w1 - w0)
    finally:
        launch.terminate()
        launch.wait(timeout=30)


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument('--steps', type=int, default=30000)
    ap.add_argument('--seconds', type=float, default=5.0, help='wall time to measure the ROS node')
    a = ap.parse_args()
    pb_default = pybullet_steps(a.steps)
    pb_10 = pybullet_steps(a.steps, iterations=10)
    rows = [
        ('car core (C++ bench_core)', core_cpp(a.steps)),
        ('car core (Python API, World.step)', core_python(a.steps)),
        ('car ROS node (sim.launch rtf:=0)', ros_node(a.seconds)),
        ('PyBullet %s, default solver (50 iterations)' % __import__('pybullet').getAPIVersion(), pb_default),
        ('PyBullet, 10 solver iterations (as car)', pb_10),
    ]
    print('physics at 1 kHz, seed car (car_camera_lidar04) in box_house, commanded v = 1 m/s, w = 1 rad/s')
    print('%-48s %12s %10s %14s %14s' % ('', 'steps/s', 'x real', 'vs PyBullet', 'vs PyB 10 it'))
    for name, rate in rows:
        print('%-48s %12.0f %10.1f %14.2f %14.2f' % (name, rate, rate / 1000.0, rate / pb_default, rate / pb_10))
    return 0


if __name__ == '__main__':
    sys.exit(main())
