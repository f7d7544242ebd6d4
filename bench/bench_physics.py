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


def pybullet_sensors(rays_total=200000):
    """PyBullet's peers of car's sensors on the same scene: rayTestBatch rays/s (1 thread and all), and
    getCameraImage frames/s at 640 x 480 with its CPU renderer."""
    import pybullet as p
    p.connect(p.DIRECT)
    pybullet_world(p, None)
    p.loadURDF(URDF, [0, 0, 0])
    origin = [0.0, 0.0, 0.27]
    th = [-3 + 6 * i / (16384 - 1) for i in range(16384)]
    to = [[origin[0] + 30 * math.cos(a), origin[1] + 30 * math.sin(a), origin[2]] for a in th]
    frm = [origin] * len(to)
    out = {}
    for threads in (1, 0):
        t = time.perf_counter()
        n = 0
        while n < rays_total:
            p.rayTestBatch(frm, to, numThreads=threads)
            n += len(to)
        out['rays_%d' % threads] = n / (time.perf_counter() - t)
    view = p.computeViewMatrix([0, 0, 0.17], [1, 0, 0.17], [0, 0, 1])
    vfov = 2 * math.degrees(math.atan(math.tan(math.radians(30)) * 480 / 640))
    proj = p.computeProjectionMatrixFOV(vfov, 640 / 480, 0.05, 8.0)
    frames, t = 0, time.perf_counter()
    while time.perf_counter() - t < 3.0:
        p.getCameraImage(640, 480, view, proj, renderer=p.ER_TINY_RENDERER)
        frames += 1
    out['camera'] = frames / (time.perf_counter() - t)
    p.disconnect()
    return out


def core_sensors(threads):
    exe = os.path.join(ROOT, '.ws', 'devel', 'lib', 'car', 'bench_sensors')
    env = dict(os.environ, OMP_NUM_THREADS=str(threads))
    out = subprocess.run([exe, URDF, WORLD, '5'], capture_output=True, text=True, check=True, env=env).stdout
    vals = {}
    for line in out.splitlines():
        if line.startswith('lidar:'):
            vals['rays'] = float(line.split('->')[1].split()[0]) * 1e6
        elif line.startswith('depth:'):
            vals['fps'] = float(line.split('->')[1].split()[0])
        elif line.startswith('full stack'):
            vals['full'] = float(line.split(':')[1].split('x')[0])
    return vals


def ros_node(seconds, cloud=False):
    """sim.launch at rtf 0: steps per wall second. With cloud, a subscriber on /camera/depth/points (and
    /scan) keeps the lidar and the Kinect (20 Hz) computing and publishing."""
    env = dict(os.environ, ROS_MASTER_URI='http://localhost:11399')
    launch = subprocess.Popen(['roslaunch', '-p', '11399', 'car', 'sim.launch', 'rtf:=0'], env=env,
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        os.environ['ROS_MASTER_URI'] = env['ROS_MASTER_URI']
        import rospy
        from rosgraph_msgs.msg import Clock
        from gazebo_msgs.srv import GetModelState
        rospy.init_node('bench_physics', anonymous=True, disable_signals=True)
        rospy.wait_for_service('/gazebo/get_model_state', timeout=60)
        get = rospy.ServiceProxy('/gazebo/get_model_state', GetModelState)
        while not get('mycar', '').success:
            time.sleep(0.1)

        subs = []
        if cloud:
            from sensor_msgs.msg import LaserScan, PointCloud2
            subs = [rospy.Subscriber('/camera/depth/points', PointCloud2, lambda m: None, queue_size=1),
                    rospy.Subscriber('/scan', LaserScan, lambda m: None, queue_size=1)]
            time.sleep(1.0)

        def sim_now():
            return rospy.wait_for_message('/clock', Clock, timeout=30).clock.to_sec()

        s0, w0 = sim_now(), time.perf_counter()
        time.sleep(seconds)
        s1, w1 = sim_now(), time.perf_counter()
        for sub in subs:
            sub.unregister()
        return (s1 - s0) / 0.001 / (w1 - w0)
    finally:
        launch.terminate()
        launch.wait(timeout=30)


def ros_node_subprocess(seconds, cloud):
    """ros_node in a fresh process: rospy initialises once per process."""
    out = subprocess.run([sys.executable, os.path.abspath(__file__), '--ros-node', 'cloud' if cloud else 'plain',
                          '--seconds', str(seconds)], capture_output=True, text=True, check=True).stdout
    return float(out.strip().splitlines()[-1])


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument('--steps', type=int, default=30000)
    ap.add_argument('--seconds', type=float, default=5.0, help='wall time to measure the ROS node')
    ap.add_argument('--no-sensors', dest='sensors', action='store_false', help='physics only')
    ap.add_argument('--ros-node', choices=('plain', 'cloud'), help=argparse.SUPPRESS)
    a = ap.parse_args()
    if a.ros_node:
        print(ros_node(a.seconds, cloud=a.ros_node == 'cloud'))
        return 0
    pb_default = pybullet_steps(a.steps)
    pb_10 = pybullet_steps(a.steps, iterations=10)
    rows = [
        ('car core (C++ bench_core)', core_cpp(a.steps)),
        ('car core (Python API, World.step)', core_python(a.steps)),
        ('car ROS node (sim.launch rtf:=0)', ros_node_subprocess(a.seconds, False)),
        ('PyBullet %s, default solver (50 iterations)' % __import__('pybullet').getAPIVersion(), pb_default),
        ('PyBullet, 10 solver iterations (as car)', pb_10),
    ]
    print('physics at 1 kHz, seed car (car_camera_lidar04) in box_house, commanded v = 1 m/s, w = 1 rad/s')
    print('%-48s %12s %10s %14s %14s' % ('', 'steps/s', 'x real', 'vs PyBullet', 'vs PyB 10 it'))
    for name, rate in rows:
        print('%-48s %12.0f %10.1f %14.2f %14.2f' % (name, rate, rate / 1000.0, rate / pb_default, rate / pb_10))
    if a.sensors:
        pb = pybullet_sensors()
        c1, c2 = core_sensors(1), core_sensors(2)
        print()
        print('sensors, same scene')
        print('%-48s %14s %14s' % ('', 'value', 'vs PyBullet'))
        print('%-48s %12.1f M %14.2f' % ('lidar rays/s, 1 core: car (Embree)', c1['rays'] / 1e6, c1['rays'] / pb['rays_1']))
        print('%-48s %12.1f M %14s' % ('lidar rays/s, 1 core: PyBullet rayTestBatch', pb['rays_1'] / 1e6, '1'))
        print('%-48s %12.1f M %14.2f' % ('lidar rays/s, 2 cores: car', c2['rays'] / 1e6, c2['rays'] / pb['rays_0']))
        print('%-48s %12.1f M %14s' % ('lidar rays/s, all cores: PyBullet', pb['rays_0'] / 1e6, '1'))
        print('%-48s %14.1f %14.2f' % ('depth+colour frames/s 640x480, 1 core: car', c1['fps'], c1['fps'] / pb['camera']))
        print('%-48s %14.1f %14.2f' % ('depth+colour frames/s 640x480, 2 cores: car', c2['fps'], c2['fps'] / pb['camera']))
        print('%-48s %14.1f %14s' % ('getCameraImage 640x480 (TinyRenderer): PyBullet', pb['camera'], '1'))
        print('%-48s %13.1fx' % ('full stack in the core (1 kHz, lidar 5.5 Hz, depth 10 Hz)', c2['full']))
        ros = ros_node_subprocess(a.seconds, True) / 1000.0
        print('%-48s %13.1fx  = %.1f clouds/s published' % ('ROS node, /scan and 20 Hz cloud subscribed', ros, ros * 20))
    return 0


if __name__ == '__main__':
    sys.exit(main())
