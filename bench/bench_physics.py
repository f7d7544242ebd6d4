#!/usr/bin/env python3
"""Physics steps/s at 1 kHz for the seed car in box_house: car's core (C++ and Python API), car's ROS node,
MuJoCo (bench_mujoco.py: the same model through MjSpec, validated first) and PyBullet (both from PyPI) stepping
the same expanded URDF and world, all measured in this run; then the sensors beside PyBullet's.

usage: bench_physics.py [--steps N] [--seconds S] [--no-sensors] [--json FILE]   (through bench/run.sh)
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
        """xyzw quaternion of a rotation matrix (Shepperd's method: the largest diagonal term first)."""
        (a, b, c), (d, e, f), (g, h, i) = rot
        tr = a + e + i
        if tr > 0:
            s = 2 * math.sqrt(tr + 1)
            return [(h - f) / s, (c - g) / s, (d - b) / s, s / 4]
        if a >= e and a >= i:
            s = 2 * math.sqrt(1 + a - e - i)
            return [s / 4, (b + d) / s, (c + g) / s, (h - f) / s]
        if e >= i:
            s = 2 * math.sqrt(1 + e - a - i)
            return [(b + d) / s, s / 4, (f + h) / s, (c - g) / s]
        s = 2 * math.sqrt(1 + i - a - e)
        return [(c + g) / s, (f + h) / s, s / 4, (d - b) / s]

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


def core_many(seconds=3.0):
    """bench_many: the largest number of seed cars (lidar 5.5 Hz computing, diff drive commanded) that one
    process steps at >= 1x real time, and the factor at each N it tried."""
    exe = os.path.join(ROOT, '.ws', 'devel', 'lib', 'car', 'bench_many')
    out = subprocess.run([exe, URDF, str(seconds)], capture_output=True, text=True, check=True).stdout
    tried = {}
    for line in out.splitlines():
        if line.startswith('cars'):
            n, x = line.split(':')
            tried[int(n.split()[1])] = float(x.split('x')[0])
        elif line.startswith('many:'):
            best = int(line.split()[1])
    return best, tried


def ros_node(seconds, cloud=False):
    """sim.launch at rtf 0 with /odom subscribed: steps per wall second. With cloud, a subscriber on
    /camera/depth/points (and /scan) keeps the lidar and the Kinect (20 Hz) computing and publishing."""
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

        # /odom subscribed, as a user's nav stack would (the diff drive publishes it at its updateRate)
        from nav_msgs.msg import Odometry
        subs = [rospy.Subscriber('/odom', Odometry, lambda m: None, queue_size=1)]
        if cloud:
            from sensor_msgs.msg import LaserScan, PointCloud2
            subs += [rospy.Subscriber('/camera/depth/points', PointCloud2, lambda m: None, queue_size=1),
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
    ap.add_argument('--json', metavar='FILE', help='also write every figure, the peers\' and the ratios to FILE')
    ap.add_argument('--ros-node', choices=('plain', 'cloud'), help=argparse.SUPPRESS)
    a = ap.parse_args()
    if a.ros_node:
        print(ros_node(a.seconds, cloud=a.ros_node == 'cloud'))
        return 0
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    import bench_mujoco
    # figures under stable keys: [steps/s] for physics, [rays/s], [frames/s], [x real time]
    fig = {}
    fig['physics.pybullet_default'] = pybullet_steps(a.steps)
    fig['physics.pybullet_10it'] = pybullet_steps(a.steps, iterations=10)
    mj_rest, mj_radius = bench_mujoco.validate()
    fig['physics.mujoco.rest_height_m'] = mj_rest
    fig['physics.mujoco.circle_radius_m'] = mj_radius
    fig['physics.mujoco'] = bench_mujoco.steps_per_second(a.steps)
    fig['physics.mujoco_sleep'] = bench_mujoco.steps_per_second(a.steps, sleep=True)
    fig['physics.car_core_cpp'] = core_cpp(a.steps)
    fig['physics.car_core_python'] = core_python(a.steps)
    fig['physics.car_ros_node'] = ros_node_subprocess(a.seconds, False)
    rows = [
        ('car core (C++ bench_core)', 'physics.car_core_cpp'),
        ('car core (Python API, World.step)', 'physics.car_core_python'),
        ('car ROS node (sim.launch rtf:=0)', 'physics.car_ros_node'),
        ('MuJoCo %s (implicitfast, sleeping off)' % bench_mujoco.version(), 'physics.mujoco'),
        ('MuJoCo, island sleeping on', 'physics.mujoco_sleep'),
        ('PyBullet %s, default solver (50 iterations)' % __import__('pybullet').getAPIVersion(),
         'physics.pybullet_default'),
        ('PyBullet, 10 solver iterations (as car)', 'physics.pybullet_10it'),
    ]
    mj_best = max(fig['physics.mujoco'], fig['physics.mujoco_sleep'])
    print('physics at 1 kHz, seed car (car_camera_lidar04) in box_house, commanded v = 1 m/s, w = 1 rad/s')
    print('MuJoCo model check (bare ground): base at rest %.4f m (car 0.055), circle radius %.3f m (car 1.000)'
          % (mj_rest, mj_radius))
    print('%-48s %12s %8s %10s %10s %10s' % ('', 'steps/s', 'x real', 'vs MuJoCo', 'vs PyB', 'vs PyB 10'))
    for name, key in rows:
        rate = fig[key]
        print('%-48s %12.0f %8.1f %10.2f %10.2f %10.2f' % (name, rate, rate / 1000.0, rate / mj_best,
                                                          rate / fig['physics.pybullet_default'],
                                                          rate / fig['physics.pybullet_10it']))
    fig['ratio.car_core_vs_mujoco_best'] = fig['physics.car_core_cpp'] / mj_best
    fig['ratio.car_core_vs_pybullet_10it'] = fig['physics.car_core_cpp'] / fig['physics.pybullet_10it']
    fig['ratio.ros_node_vs_core'] = fig['physics.car_ros_node'] / fig['physics.car_core_cpp']
    print('%-48s %12.2f' % ('ROS node / core', fig['ratio.ros_node_vs_core']))
    if a.sensors:
        pb = pybullet_sensors()
        c1, c2 = core_sensors(1), core_sensors(2)
        fig.update({'lidar.car_1core_rays_per_s': c1['rays'], 'lidar.car_2core_rays_per_s': c2['rays'],
                    'lidar.pybullet_1thread_rays_per_s': pb['rays_1'], 'lidar.pybullet_all_rays_per_s': pb['rays_0'],
                    'depth.car_1core_fps': c1['fps'], 'depth.car_2core_fps': c2['fps'],
                    'depth.pybullet_tinyrenderer_fps': pb['camera'], 'full_stack.core_x_real_time': c2['full']})
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
        best, tried = core_many()
        fig['many.cars_at_1x_real_time'] = best
        fig['many.x_real_time_by_cars'] = {str(k): v for k, v in sorted(tried.items())}
        print('%-48s %14d  (%s)' % ('seed cars with lidar + drive at >= 1x, one process', best,
                                    ', '.join('%d: %.2fx' % kv for kv in sorted(tried.items()))))
        ros = ros_node_subprocess(a.seconds, True) / 1000.0
        fig['full_stack.ros_cloud_x_real_time'] = ros
        print('%-48s %13.1fx  = %.1f clouds/s published' % ('ROS node, /scan and 20 Hz cloud subscribed', ros, ros * 20))
    if a.json:
        import json
        import platform
        fig['machine'] = {'cpus': os.cpu_count(), 'platform': platform.platform(),
                          'load_average_1min': os.getloadavg()[0]}
        with open(a.json, 'w') as f:
            json.dump(fig, f, indent=1, sort_keys=True)
        print('figures written to %s' % a.json)
        import table
        print()
        print(table.render(fig))
    return 0


if __name__ == '__main__':
    sys.exit(main())
