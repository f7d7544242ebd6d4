#!/usr/bin/env python3
"""Physics steps/s at 1 kHz for the seed car in box_house: car's core (C++ and Python API), car's ROS node,
MuJoCo (bench_mujoco.py: the same model through MjSpec, validated first) and PyBullet (both from PyPI) stepping
the same expanded URDF and world, all measured in this run; then the sensors beside PyBullet's.

Method: every measurement (car's and its peers') is taken N times (--repeat, default 5) in interleaved rounds, each
round running every measurement once in an order rotated by one from the round before (A B C, B C A, C A B, ...),
so a slow period of this shared machine hits car and its peers alike; each figure is the best of its N samples (the
machine's other load only ever slows a run down) and its median is reported beside it. Ratios are of the bests
(and, under RATIO.median, of the medians). The physics rows also give steps per CPU second of the stepping thread
(KEY.cpu): well above the wall figure, the thread waited for a core.

The many-robots search (bench_many, a bisection of about 35 s) runs in the first --many-repeat rounds only (default
2), to keep a run near 5 minutes on a quiet machine.

usage: bench_physics.py [--repeat N] [--many-repeat M] [--steps N] [--seconds S] [--no-sensors] [--json FILE]   (through bench/run.sh)
"""
import argparse
import math
import os
import statistics
import signal
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
URDF = os.path.join(ROOT, 'test', 'data', 'car_camera_lidar04.urdf')
WORLD = os.path.join(ROOT, 'worlds', 'box_house.world')
# the repository (car's package is its folder car/) and the catkin workspace's programs (tools/setup.sh builds .ws/)
REPO = os.path.dirname(ROOT)
PROGRAMS = os.path.join(REPO, '.ws', 'devel', 'lib', 'car')
SETTLE = 3000  # steps before timing: resting world objects may fall asleep in either engine


def round_order(names, r):
    """The order of the measurements `names` in round r (0-based): rotated left by r, so that over len(names)
    rounds each measurement runs once in every position."""
    k = r % len(names) if names else 0
    return list(names[k:]) + list(names[:k])


def interleaved(measurements, repeat, log=None):
    """Runs each of `measurements` ([(name, function)] or [(name, function, rounds)], each function returning
    {key: value}) in `repeat` rounds, in an order rotated each round (round_order); a measurement with `rounds`
    runs in the first `rounds` rounds only (a long one, to keep the run short). Returns {key: [value of each round
    it ran in, in round order]}."""
    funcs = {m[0]: m[1] for m in measurements}
    rounds = {m[0]: m[2] if len(m) > 2 else repeat for m in measurements}
    names = [m[0] for m in measurements]
    samples = {}
    for r in range(repeat):
        for name in round_order(names, r):
            if r >= rounds[name]:
                continue
            t = time.perf_counter()
            for key, value in funcs[name]().items():
                samples.setdefault(key, []).append(value)
            if log:
                log('round %d/%d: %s (%.1f s)' % (r + 1, repeat, name, time.perf_counter() - t))
    return samples


def summary(samples, cost=False):
    """(best, median) of a figure's samples: the largest for a rate (more is better, and load only lowers it), the
    smallest for a cost (cost=True: µs, %), and the median."""
    return (min(samples) if cost else max(samples)), statistics.median(samples)


def is_cost(key):
    """A figure where less is better: a time [us] or an overhead [%]."""
    return key.endswith(('_us', '_pct'))


def record(fig, samples):
    """Writes each key's best under its stable name, and KEY.median and KEY.samples beside it."""
    for key, values in samples.items():
        fig[key], fig[key + '.median'] = summary(values, is_cost(key))
        fig[key + '.samples'] = list(values)


def core_python(steps, world=WORLD):
    """(steps per wall second, per CPU second of the stepping thread) of World.step(steps) on a fresh world
    (box_house; None: Gazebo's empty world, a bare ground plane)."""
    from car import _core
    w = _core.World(world)
    with open(URDF) as f:
        w.spawn_urdf(f.read(), 'mycar')
    w.set_cmd_vel('mycar', 1.0, 1.0)
    w.step(SETTLE)
    # World.step releases the GIL but steps in this thread, so this thread's CPU time is the stepping's
    t, c = time.perf_counter(), time.thread_time()
    w.step(steps)
    c, t = time.thread_time() - c, time.perf_counter() - t
    return steps / t, steps / max(c, 1e-9)


def parse_core(out):
    """(steps per wall second, per CPU second) from bench_core's line
    'core: R steps/s = ... (N steps in S s; C steps per CPU second)'; C is None from an older bench_core."""
    words = out.split()
    cpu = float(words[words.index('per') - 2]) if 'CPU' in words else None
    return float(words[1]), cpu


def core_cpp(steps, world=WORLD):
    """bench_core's rates in a world (box_house; None: the empty world)."""
    exe = os.path.join(PROGRAMS, 'bench_core')
    out = subprocess.run([exe, URDF, world or '-', str(steps)], capture_output=True, text=True, check=True).stdout
    return parse_core(out)


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


def flush_c_stdout():
    """Ends and writes out what PyBullet printed through C's stdio buffer (its URDF warnings end in a link name and
    no newline), so that it does not run into this script's next line (bench/run.sh filters those warnings by
    line)."""
    import ctypes
    sys.stdout.flush()
    libc = ctypes.CDLL(None)
    libc.puts(b'')
    libc.fflush(None)


def pybullet_steps(steps, iterations=None):
    import pybullet as p
    p.connect(p.DIRECT)
    pybullet_world(p, iterations)
    car = p.loadURDF(URDF, [0, 0, 0])
    flush_c_stdout()
    joints = {p.getJointInfo(car, i)[1].decode(): i for i in range(p.getNumJoints(car))}
    for j in joints.values():
        p.setJointMotorControl2(car, j, p.VELOCITY_CONTROL, targetVelocity=0, force=0)
    r, sep = 0.0325, 0.2
    p.setJointMotorControl2(car, joints['left2link'], p.VELOCITY_CONTROL, targetVelocity=(1 - sep / 2) / r, force=30)
    p.setJointMotorControl2(car, joints['right2link'], p.VELOCITY_CONTROL, targetVelocity=(1 + sep / 2) / r, force=30)
    for _ in range(SETTLE):
        p.stepSimulation()
    # DIRECT mode steps in this thread
    t, c = time.perf_counter(), time.thread_time()
    for _ in range(steps):
        p.stepSimulation()
    c, t = time.thread_time() - c, time.perf_counter() - t
    p.disconnect()
    return steps / t, steps / max(c, 1e-9)


def pybullet_sensors(rays_total=200000):
    """PyBullet's peers of car's sensors on the same scene: rayTestBatch rays/s (1 thread and all), and
    getCameraImage frames/s at 640 x 480 with its CPU renderer."""
    import pybullet as p
    p.connect(p.DIRECT)
    pybullet_world(p, None)
    p.loadURDF(URDF, [0, 0, 0])
    flush_c_stdout()
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
    exe = os.path.join(PROGRAMS, 'bench_sensors')
    env = dict(os.environ, OMP_NUM_THREADS=str(threads))
    out = subprocess.run([exe, URDF, WORLD, '5'], capture_output=True, text=True, check=True, env=env).stdout
    return parse_sensors(out)


def parse_sensors(out):
    """{'rays': rays/s, 'fps': frames/s, 'depth_alone_fps': frames/s of the depth image alone, 'full': x real
    time} from bench_sensors' lines."""
    vals = {}
    for line in out.splitlines():
        if line.startswith('lidar:'):
            vals['rays'] = float(line.split('->')[1].split()[0]) * 1e6
        elif line.startswith('depth:'):
            vals['fps'] = float(line.split('->')[1].split()[0])
        elif line.startswith('depth image alone:'):
            vals['depth_alone_fps'] = float(line.split('->')[1].split()[0])
        elif line.startswith('full stack'):
            vals['full'] = float(line.split(':')[1].split('x')[0])
    return vals


def core_many(seconds=3.0):
    """bench_many: the largest number of seed cars (lidar 5.5 Hz computing, diff drive commanded) that one
    process steps at >= 1x real time, and the factor at each N it tried."""
    exe = os.path.join(PROGRAMS, 'bench_many')
    out = subprocess.run([exe, URDF, str(seconds)], capture_output=True, text=True, check=True).stdout
    tried = {}
    for line in out.splitlines():
        if line.startswith('cars'):
            n, x = line.split(':')
            tried[int(n.split()[1])] = float(x.split('x')[0])
        elif line.startswith('many:'):
            best = int(line.split()[1])
    return best, tried


def gazebo_plugins(rounds=9, steps=2000):
    """bench_gazebo: the seed car's step cost [us of the stepping thread's CPU] with 0, 1 and 10 model plug-ins
    whose WorldUpdateBegin callback is empty (bench/plugins/empty_update.cc), medians of its own interleaved rounds;
    one callback's cost [us] and ten plug-ins' overhead [% of the step with none]."""
    exe = os.path.join(PROGRAMS, 'bench_gazebo')
    plugins = os.path.join(PROGRAMS, 'bench_plugins')
    out = subprocess.run([exe, URDF, WORLD, plugins, str(rounds), str(steps)], capture_output=True, text=True,
                         check=True).stdout
    return parse_gazebo(out)


def parse_gazebo(out):
    """{key: value} from bench_gazebo's lines 'gazebo: step cost, ...: 0 plug-ins A us, 1 B us, 10 C us' and
    'gazebo: one empty WorldUpdateBegin callback D us per step (...); ten plug-ins E % of ...'."""
    import re
    m = re.search(r'0 plug-ins ([0-9.]+) us, 1 ([0-9.]+) us, 10 ([0-9.]+) us', out)
    c = re.search(r'callback (-?[0-9.]+) us per step .*ten plug-ins ([-+0-9.]+) %', out)
    if not m or not c:
        raise RuntimeError('bench_gazebo printed no figures: %r' % out)
    return {'gazebo.step_0_plugins_us': float(m.group(1)), 'gazebo.step_1_plugin_us': float(m.group(2)),
            'gazebo.step_10_plugins_us': float(m.group(3)), 'gazebo.callback_us': float(c.group(1)),
            'gazebo.ten_plugins_overhead_pct': float(c.group(2))}


def stat_fields(path):
    """The fields of a /proc stat file after the command name (state, ppid, ...), or None when it is gone."""
    try:
        return open(path).read().rsplit(')', 1)[1].split()
    except (OSError, IndexError):
        return None


def proc_cpu(pid, tid=None):
    """[s] CPU time (user + system) of a process, or of one of its threads, from /proc; 0 when it is gone."""
    fields = stat_fields('/proc/%d/task/%d/stat' % (pid, tid) if tid else '/proc/%d/stat' % pid)
    return (int(fields[11]) + int(fields[12])) / os.sysconf('SC_CLK_TCK') if fields else 0.0


def children(pid):
    """Pids of a process's direct children."""
    out = []
    for d in os.listdir('/proc'):
        if d.isdigit():
            fields = stat_fields('/proc/%s/stat' % d)
            if fields and int(fields[1]) == pid:
                out.append(int(d))
    return out


def ros_node(seconds, kind='plain'):
    """The node at rtf 0, the car commanded as in the core's row (v = 1 m/s, w = 1 rad/s), /odom subscribed: steps per
    wall second, and per CPU second of the node's stepping thread. kind 'plain': sim.launch; 'alone':
    bench/node_alone.launch (the simulator and the car without sim.launch's consumers robot_state_publisher,
    world_markers and the static transform); 'cloud': sim.launch with /camera/depth/points (and /scan) subscribed
    too, which keeps the lidar and the Kinect (20 Hz) computing and publishing. On stderr: where the CPU went per
    sim second (the stepping thread, the node's other threads, the launch's other nodes and the subscriber)."""
    env = dict(os.environ, ROS_MASTER_URI='http://localhost:11399')
    cloud = kind == 'cloud'
    what = [os.path.join(ROOT, 'bench', 'node_alone.launch')] if kind == 'alone' else ['car', 'sim.launch', 'rtf:=0']
    launch = subprocess.Popen(['roslaunch', '-p', '11399'] + what, env=env,
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    listen = None
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
        node = [p for p in children(launch.pid) if b'sim_node' in open('/proc/%d/cmdline' % p, 'rb').read()][0]

        # /odom subscribed, as a user's nav stack would (the diff drive publishes it at its updateRate); with cloud,
        # /scan and the Kinect's cloud too. The subscriber is bench_listen (C++, TCP_NODELAY, as rviz or a nav
        # stack would be): a rospy subscriber spent about as much CPU on the 10 MB clouds as the simulator did.
        # It also sends the core row's command on /cmd_vel (latched), so the node steps the same motion.
        listen = subprocess.Popen([os.path.join(PROGRAMS, 'bench_listen'), '--cmd', '1', '1']
                                  + (['--cloud'] if cloud else []), env=env, stdout=subprocess.PIPE,
                                  stderr=subprocess.DEVNULL, text=True)
        time.sleep(1.0)

        def sim_now():
            return rospy.wait_for_message('/clock', Clock, timeout=30).clock.to_sec()

        others = [p for p in children(launch.pid) if p != node] + [listen.pid]

        def cpu():
            return proc_cpu(node, node), proc_cpu(node), sum(proc_cpu(p) for p in others)

        def program(pid):
            """A process's program name: the node's __name, else its executable's file name."""
            try:
                argv = open('/proc/%d/cmdline' % pid, 'rb').read().decode(errors='replace').split('\0')
            except OSError:
                return str(pid)
            names = [a[len('__name:='):] for a in argv if a.startswith('__name:=')]
            script = [a for a in argv[1:2] if argv[0].endswith('python3')]
            return names[0] if names else os.path.basename((script or argv)[0])

        names = {p: program(p) for p in others}
        each0 = {p: proc_cpu(p) for p in others}
        s0, w0, c0 = sim_now(), time.perf_counter(), cpu()
        time.sleep(seconds)
        s1, w1, c1 = sim_now(), time.perf_counter(), cpu()
        each1 = {p: proc_cpu(p) for p in others}
        listen.send_signal(signal.SIGINT)
        got = listen.communicate(timeout=30)[0].split()
        counts = dict(zip(got[0::2], (int(x) for x in got[1::2])))
        # what the subscriber received, per sim second of the whole subscription (a check that it kept up)
        tag = '' if kind == 'plain' else ' ' + kind
        print('ros_node%s: received %s over about %.1f sim s' % (tag, counts, s1), file=sys.stderr)
        step, proc, rest = (b - a for a, b in zip(c0, c1))
        sim = s1 - s0
        print('ros_node%s: CPU per sim second: stepping thread %.1f ms, the node\'s other threads %.1f ms, the launch\'s '
              'other nodes and the subscriber %.1f ms' % (tag, 1e3 * step / sim,
                                                         1e3 * (proc - step) / sim, 1e3 * rest / sim), file=sys.stderr)
        # each of the other processes (the master, rosout, robot_state_publisher, world_markers, the static
        # transform, the subscriber), so what the second core spends is named
        print('ros_node%s: CPU per sim second of each other process: %s' % (tag, ', '.join(
            '%s %.2f ms' % (names[p], 1e3 * (each1[p] - each0[p]) / sim) for p in others if each1[p] > 0)),
            file=sys.stderr)
        if cloud and counts.get('clouds', 0) == 0:
            raise RuntimeError('bench_listen received no cloud')
        steps = sim / 0.001
        return steps / (w1 - w0), steps / max(step, 1e-9)
    finally:
        if listen is not None and listen.poll() is None:
            listen.kill()
            listen.wait()
        launch.terminate()
        launch.wait(timeout=30)


def ros_node_subprocess(seconds, kind):
    """ros_node in a fresh process (rospy initialises once per process): (steps per wall second, per CPU second of
    the stepping thread)."""
    out = subprocess.run([sys.executable, os.path.abspath(__file__), '--ros-node', kind,
                          '--seconds', str(seconds)], stdout=subprocess.PIPE, text=True, check=True).stdout
    wall, cpu = out.strip().splitlines()[-1].split()
    return float(wall), float(cpu)


def measurements(a):
    """The interleaved measurements of a run: [(name, function returning {key: value})]. Each builds its model or
    starts its process afresh, so every round times the same work."""
    import bench_mujoco

    def pair(key, rates):
        wall, cpu = rates
        return {key: wall, key + '.cpu': cpu} if cpu else {key: wall}

    m = [
        ('car core C++', lambda: pair('physics.car_core_cpp', core_cpp(a.steps))),
        ('car core Python', lambda: pair('physics.car_core_python', core_python(a.steps))),
        ('car core C++, bare plane', lambda: pair('physics.car_core_cpp_plane', core_cpp(a.steps, None))),
        ('car core Python, bare plane', lambda: pair('physics.car_core_python_plane', core_python(a.steps, None))),
        # the peer the ratios use (bench_mujoco.py: the strongest faithful model), in this process like the
        # Python core rows
        ('MuJoCo strong', lambda: pair('physics.mujoco_strong', bench_mujoco.rates(a.steps, peer='strong'))),
        ('MuJoCo strong, bare plane', lambda: pair('physics.mujoco_strong_plane',
                                                   bench_mujoco.rates(a.steps, peer='strong', world_file=None))),
        # the old model, for comparison
        ('MuJoCo', lambda: pair('physics.mujoco', bench_mujoco.rates(a.steps))),
        ('MuJoCo sleeping', lambda: pair('physics.mujoco_sleep', bench_mujoco.rates(a.steps, sleep=True))),
        ('MuJoCo, bare plane', lambda: pair('physics.mujoco_plane', bench_mujoco.rates(a.steps, world_file=None))),
        ('PyBullet', lambda: pair('physics.pybullet_default', pybullet_steps(a.steps))),
        ('PyBullet 10 it.', lambda: pair('physics.pybullet_10it', pybullet_steps(a.steps, iterations=10))),
        ('car ROS node', lambda: pair('physics.car_ros_node', ros_node_subprocess(a.seconds, 'plain'))),
        ('car ROS node alone', lambda: pair('physics.car_ros_node_alone', ros_node_subprocess(a.seconds, 'alone'))),
        ('car Gazebo plug-ins', gazebo_plugins),
    ]
    if a.sensors:
        def sensors(threads):
            c = core_sensors(threads)
            n = '%dcore' % threads
            out = {'lidar.car_%s_rays_per_s' % n: c['rays'], 'depth.car_%s_fps' % n: c['fps']}
            if 'depth_alone_fps' in c:
                out['depth.car_%s_depth_image_alone_fps' % n] = c['depth_alone_fps']
            if threads == 2:
                out['full_stack.core_x_real_time'] = c['full']
            return out

        def pb_sensors():
            pb = pybullet_sensors()
            return {'lidar.pybullet_1thread_rays_per_s': pb['rays_1'], 'lidar.pybullet_all_rays_per_s': pb['rays_0'],
                    'depth.pybullet_tinyrenderer_fps': pb['camera']}

        def many():
            best, tried = core_many()
            out = {'many.cars_at_1x_real_time': best}
            out.update({'many.x_real_time_by_cars.%d' % k: v for k, v in tried.items()})
            return out

        m += [
            ('car sensors, 1 core', lambda: sensors(1)),
            ('car sensors, 2 cores', lambda: sensors(2)),
            ('PyBullet sensors', pb_sensors),
            ('car ROS node with cloud', lambda: {'full_stack.ros_cloud_x_real_time':
                                                 ros_node_subprocess(a.seconds, 'cloud')[0] / 1000.0}),
            ('car many robots', many, min(a.repeat, a.many_repeat)),
        ]
    return m


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('--repeat', type=int, default=5, metavar='N',
                    help='interleaved rounds; each figure is the best of N (default 5)')
    ap.add_argument('--many-repeat', type=int, default=2, metavar='M',
                    help='rounds that run the many-robots search (about 35 s each on a quiet machine; default 2)')
    ap.add_argument('--steps', type=int, default=30000, help='physics steps timed per sample (default 30000)')
    ap.add_argument('--seconds', type=float, default=5.0, help='wall time to measure the ROS node per sample')
    ap.add_argument('--no-sensors', dest='sensors', action='store_false', help='physics only')
    ap.add_argument('--json', metavar='FILE', help='also write every figure, the peers\' and the ratios to FILE')
    ap.add_argument('--ros-node', choices=('plain', 'cloud', 'alone'), help=argparse.SUPPRESS)
    a = ap.parse_args()
    if a.ros_node:
        print('%f %f' % ros_node(a.seconds, a.ros_node))
        return 0
    if a.repeat < 1 or a.many_repeat < 1:
        ap.error('--repeat and --many-repeat must be at least 1')
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    import bench_mujoco
    # figures under stable keys: [steps/s] for physics, [rays/s], [frames/s], [x real time]; each the best of
    # a.repeat interleaved samples, with KEY.median and KEY.samples; KEY.cpu: per CPU second of the stepping thread
    many_rounds = min(a.repeat, a.many_repeat)
    fig = {'bench.repeat': a.repeat,
           'bench.method': 'best of %d interleaved rounds (order rotated each round); median beside it' % a.repeat}
    if a.sensors:
        fig['bench.many_repeat'] = many_rounds
        fig['bench.method'] += '; the many-robots search in %d of the rounds' % many_rounds
    # the peers are validated against car before they are timed (bench_mujoco.validate: the same measurements of
    # both engines); the strong model's figures under physics.mujoco_strong.validation.*, car's under .car.*
    for peer, key in (('strong', 'physics.mujoco_strong.validation'), ('old', 'physics.mujoco.validation')):
        v = bench_mujoco.validate(peer)
        bench_mujoco.print_validation(v, peer)
        for k, x in v.items():
            fig['%s.%s' % (key, k)] = x
    t0 = time.perf_counter()
    load_start, loads = os.getloadavg()[0], []

    def log(line):
        # the machine's 1-minute load average after each measurement: how busy the other tenants were
        loads.append(os.getloadavg()[0])
        print('%s, load %.1f' % (line, loads[-1]), flush=True)
    samples = interleaved(measurements(a), a.repeat, log=log)
    many = {k: v for k, v in samples.items() if k.startswith('many.x_real_time_by_cars.')}
    for k in many:
        del samples[k]
    record(fig, samples)
    if many:
        # each round bisects on its own, so rounds try different car counts: the best factor at each count tried
        fig['many.x_real_time_by_cars'] = {k.rsplit('.', 1)[1]: max(v)
                                           for k, v in sorted(many.items(), key=lambda kv: int(kv[0].rsplit('.', 1)[1]))}
    fig['bench.seconds'] = time.perf_counter() - t0
    rows = [
        ('car core (C++ bench_core)', 'physics.car_core_cpp'),
        ('car core (Python API, World.step)', 'physics.car_core_python'),
        ('car ROS node (sim.launch rtf:=0)', 'physics.car_ros_node'),
        ('car ROS node alone (bench/node_alone.launch)', 'physics.car_ros_node_alone'),
        ('MuJoCo %s, strong model (the peer)' % bench_mujoco.version(), 'physics.mujoco_strong'),
        ('MuJoCo, old model, sleeping off', 'physics.mujoco'),
        ('MuJoCo, old model, island sleeping on', 'physics.mujoco_sleep'),
        ('PyBullet %s, default solver (50 iterations)' % __import__('pybullet').getAPIVersion(),
         'physics.pybullet_default'),
        ('PyBullet, 10 solver iterations (as car)', 'physics.pybullet_10it'),
    ]
    mj_best = fig['physics.mujoco_strong']
    mj_median = fig['physics.mujoco_strong.median']
    print()
    print('physics at 1 kHz, seed car (car_camera_lidar04) in box_house, commanded v = 1 m/s, w = 1 rad/s;')
    print(fig['bench.method'])
    print('"vs MuJoCo": against the strong model (validated above)')
    print('%-44s %9s %9s %9s %7s %9s %7s %9s' % ('', 'best/s', 'median/s', 'CPU s/s', 'x real', 'vs MuJoCo',
                                               'vs PyB', 'vs PyB 10'))
    for name, key in rows:
        rate = fig[key]
        cpu = fig.get(key + '.cpu')
        print('%-44s %9.0f %9.0f %9s %7.1f %9.2f %7.2f %9.2f' % (
            name, rate, fig[key + '.median'], '%.0f' % cpu if cpu else '-', rate / 1000.0, rate / mj_best,
            rate / fig['physics.pybullet_default'], rate / fig['physics.pybullet_10it']))
    print()
    print('bare ground plane, same car and command')
    for name, key, peer in (('car core (C++ bench_core)', 'physics.car_core_cpp_plane', 'physics.mujoco_strong_plane'),
                            ('car core (Python API, World.step)', 'physics.car_core_python_plane',
                             'physics.mujoco_strong_plane'),
                            ('MuJoCo, strong model (the peer)', 'physics.mujoco_strong_plane', None),
                            ('MuJoCo, old model', 'physics.mujoco_plane', None)):
        print('%-44s %9.0f %9.0f %9s %7.1f %9s' % (
            name, fig[key], fig[key + '.median'], '%.0f' % fig[key + '.cpu'] if key + '.cpu' in fig else '-',
            fig[key] / 1000.0, '%.2f' % (fig[key] / fig[peer]) if peer else ''))
    # core against the strong peer, in box_house and on the bare plane; the Python rows were measured in the same
    # process as MuJoCo, interleaved with it
    for sfx in ('', '_plane'):
        for lang in ('cpp', 'python'):
            core, peer = 'physics.car_core_%s%s' % (lang, sfx), 'physics.mujoco_strong%s' % sfx
            fig['ratio.car_core_%s_vs_mujoco_strong%s' % (lang, sfx)] = fig[core] / fig[peer]
            fig['ratio.car_core_%s_vs_mujoco_strong%s.median' % (lang, sfx)] = (fig[core + '.median']
                                                                             / fig[peer + '.median'])
    fig['ratio.mujoco_strong_vs_old'] = fig['physics.mujoco_strong'] / max(fig['physics.mujoco'],
                                                                           fig['physics.mujoco_sleep'])
    fig['ratio.mujoco_strong_vs_old_plane'] = fig['physics.mujoco_strong_plane'] / fig['physics.mujoco_plane']
    for k in ('ratio.car_core_cpp_vs_mujoco_strong', 'ratio.car_core_python_vs_mujoco_strong',
              'ratio.car_core_cpp_vs_mujoco_strong_plane', 'ratio.car_core_python_vs_mujoco_strong_plane'):
        print('%-44s %9.2f %9.2f' % (k[len('ratio.'):] + ' (best, median)', fig[k], fig[k + '.median']))
    print('%-44s %9.2f %9.2f' % ('MuJoCo strong / old model, box_house, plane', fig['ratio.mujoco_strong_vs_old'],
                                 fig['ratio.mujoco_strong_vs_old_plane']))
    fig['ratio.car_core_vs_mujoco_best'] = fig['physics.car_core_cpp'] / mj_best
    fig['ratio.car_core_vs_pybullet_10it'] = fig['physics.car_core_cpp'] / fig['physics.pybullet_10it']
    fig['ratio.ros_node_vs_core'] = fig['physics.car_ros_node'] / fig['physics.car_core_cpp']
    fig['ratio.car_core_vs_mujoco_best.median'] = fig['physics.car_core_cpp.median'] / mj_median
    fig['ratio.car_core_vs_pybullet_10it.median'] = (fig['physics.car_core_cpp.median']
                                                     / fig['physics.pybullet_10it.median'])
    fig['ratio.ros_node_vs_core.median'] = fig['physics.car_ros_node.median'] / fig['physics.car_core_cpp.median']
    fig['ratio.ros_node_alone_vs_core'] = fig['physics.car_ros_node_alone'] / fig['physics.car_core_cpp']
    fig['ratio.ros_node_alone_vs_core.median'] = (fig['physics.car_ros_node_alone.median']
                                                  / fig['physics.car_core_cpp.median'])
    fig['ratio.car_core_python_vs_cpp'] = fig['physics.car_core_python'] / fig['physics.car_core_cpp']
    if 'physics.car_core_cpp.cpu' in fig:
        # per CPU second of the stepping thread: what the machine's other load changes least (it still shares caches)
        fig['ratio.car_core_vs_mujoco_best.cpu'] = fig['physics.car_core_cpp.cpu'] / fig['physics.mujoco_strong.cpu']
        fig['ratio.car_core_cpp_vs_mujoco_strong_plane.cpu'] = (fig['physics.car_core_cpp_plane.cpu']
                                                                / fig['physics.mujoco_strong_plane.cpu'])
        print('%-44s %9.2f' % ('core / MuJoCo per CPU second, bare plane', fig['ratio.car_core_cpp_vs_mujoco_strong_plane.cpu']))
        fig['ratio.car_core_vs_pybullet_10it.cpu'] = fig['physics.car_core_cpp.cpu'] / fig['physics.pybullet_10it.cpu']
        print('%-44s %9.2f %9.2f' % ('core / MuJoCo, / PyBullet 10 it. per CPU second',
                                     fig['ratio.car_core_vs_mujoco_best.cpu'],
                                     fig['ratio.car_core_vs_pybullet_10it.cpu']))
    print('%-44s %9.2f %9.2f' % ('ROS node / core (best, median)', fig['ratio.ros_node_vs_core'],
                                 fig['ratio.ros_node_vs_core.median']))
    print('%-44s %9.2f %9.2f' % ('ROS node alone / core (best, median)', fig['ratio.ros_node_alone_vs_core'],
                                 fig['ratio.ros_node_alone_vs_core.median']))
    if 'physics.car_ros_node.cpu' in fig and 'physics.car_core_cpp.cpu' in fig:
        # the node's stepping thread against the core's, per CPU second of each: what the node adds to a step
        # itself, apart from the second core the rest of the ROS graph needs
        fig['ratio.ros_node_vs_core.cpu'] = fig['physics.car_ros_node.cpu'] / fig['physics.car_core_cpp.cpu']
        print('%-44s %9.2f' % ('ROS node / core per CPU second (best)', fig['ratio.ros_node_vs_core.cpu']))
    if 'physics.car_ros_node_alone.cpu' in fig and 'physics.car_core_cpp.cpu' in fig:
        fig['ratio.ros_node_alone_vs_core.cpu'] = (fig['physics.car_ros_node_alone.cpu']
                                                   / fig['physics.car_core_cpp.cpu'])
        print('%-44s %9.2f' % ('ROS node alone / core per CPU second (best)', fig['ratio.ros_node_alone_vs_core.cpu']))
    print('%-44s %9.2f %9.2f' % ('core Python / C++ (best, median)', fig['ratio.car_core_python_vs_cpp'],
                                 fig['physics.car_core_python.median'] / fig['physics.car_core_cpp.median']))
    print()
    print('users\' Gazebo plug-ins: the seed car with 0, 1, 10 empty WorldUpdateBegin callbacks (bench_gazebo; '
          'each sample the median of its own interleaved rounds; best and median of the samples)')
    for name, key, unit in (('step, no plug-in', 'gazebo.step_0_plugins_us', 'us'),
                            ('step, 1 plug-in', 'gazebo.step_1_plugin_us', 'us'),
                            ('step, 10 plug-ins', 'gazebo.step_10_plugins_us', 'us'),
                            ('one empty callback (issue 49: <= 1 us)', 'gazebo.callback_us', 'us'),
                            ('10 plug-ins, % of the step (issue 49: <= 10 %)', 'gazebo.ten_plugins_overhead_pct', '%')):
        print('%-48s %10.3f %-2s (median %.3f)' % (name, fig[key], unit, fig[key + '.median']))
    if a.sensors:
        f = fig
        pb1, pb0, pbc = (f['lidar.pybullet_1thread_rays_per_s'], f['lidar.pybullet_all_rays_per_s'],
                         f['depth.pybullet_tinyrenderer_fps'])
        print()
        print('sensors, same scene (best; median)')
        print('%-48s %14s %14s' % ('', 'value', 'vs PyBullet'))

        def line(name, key, scale, unit, peer):
            v = f[key]
            print('%-48s %12.2f%s %14s   (median %.2f)' % (name, v / scale, unit,
                                                         '%.2f' % (v / peer) if peer else '1', f[key + '.median'] / scale))
        line('lidar rays/s, 1 core: car (fan sweep)', 'lidar.car_1core_rays_per_s', 1e6, ' M', pb1)
        line('lidar rays/s, 1 core: PyBullet rayTestBatch', 'lidar.pybullet_1thread_rays_per_s', 1e6, ' M', None)
        line('lidar rays/s, 2 cores: car', 'lidar.car_2core_rays_per_s', 1e6, ' M', pb0)
        line('lidar rays/s, all cores: PyBullet', 'lidar.pybullet_all_rays_per_s', 1e6, ' M', None)
        line('depth+colour frames/s 640x480, 1 core: car', 'depth.car_1core_fps', 1, '  ', pbc)
        line('depth+colour frames/s 640x480, 2 cores: car', 'depth.car_2core_fps', 1, '  ', pbc)
        if 'depth.car_2core_depth_image_alone_fps' in f:
            line('depth image alone frames/s 640x480, 2 cores: car', 'depth.car_2core_depth_image_alone_fps', 1, '  ',
                 pbc)
        line('getCameraImage 640x480 (TinyRenderer): PyBullet', 'depth.pybullet_tinyrenderer_fps', 1, '  ', None)
        line('full stack in the core (1 kHz, lidar 5.5 Hz, depth 10 Hz) [x]', 'full_stack.core_x_real_time', 1, 'x',
             None)
        print('%-48s %14d  (median %g; best factor at each count: %s)' % (
            'seed cars with lidar + drive at >= 1x, one process', f['many.cars_at_1x_real_time'],
            f['many.cars_at_1x_real_time.median'],
            ', '.join('%s: %.2fx' % kv for kv in f['many.x_real_time_by_cars'].items())))
        ros = f['full_stack.ros_cloud_x_real_time']
        print('%-48s %13.1fx  = %.1f clouds/s published  (median %.1fx)' % (
            'ROS node, /scan and 20 Hz cloud subscribed', ros, ros * 20, f['full_stack.ros_cloud_x_real_time.median']))
    print('run time of the interleaved rounds: %.0f s' % fig['bench.seconds'])
    if a.json:
        import json
        import platform
        fig['machine'] = {'cpus': os.cpu_count(), 'platform': platform.platform(),
                          'load_average_1min': os.getloadavg()[0], 'load_average_1min_start': load_start,
                          'load_average_1min_after_each': loads,
                          'env': {k: v for k, v in os.environ.items() if k.startswith(('OMP_', 'GOMP_', 'MALLOC_'))}}
        with open(a.json, 'w') as f:
            json.dump(fig, f, indent=1, sort_keys=True)
        print('figures written to %s' % a.json)
        import table
        print()
        print(table.render(fig))
    return 0


if __name__ == '__main__':
    sys.exit(main())
