"""Faults survived (a benchmark with figures, not a test): sim_node under hostile use, each on its own master.

  spawn-delete  N spawn_urdf_model + delete_model cycles of the tutorial's one-box robot (urdf/demo.urdf) into the
                empty world at rtf 0: sim_node's resident memory after the first 1000 cycles and at the end, and
                whether /clock still advances afterwards
  services      N gazebo service calls at once from T threads (get_world_properties, get_model_state,
                get_physics_properties, get_link_state in turn) against the tutorial car in box_house at rtf 0:
                how many were answered, how many failed, the slowest answer, and whether the node is still there
  cmd-vel       /cmd_vel published as fast as the publisher can, up to R Hz, for S wall seconds against the tutorial
                car in box_house at rtf 1: the rate reached and sim_node's real-time factor over the flood

Usage: bash bench/faults.sh spawn-delete [--cycles 10000] | services [--calls 1000] [--threads 50]
       | cmd-vel [--rate 10000] [--seconds 60]
Prints one `faults:` line per figure; docs/RELIABILITY.md "Faults survived" has the last run."""
import argparse
import os
import signal
import subprocess
import sys
import threading
import time
import xmlrpc.client

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from soak import free_port, rss_mb  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


class Sim:
    """roslaunch of one of car's launch files on a free port, and sim_node's pid."""

    def __init__(self, launch_args, log_name):
        port = free_port()
        os.environ['ROS_MASTER_URI'] = 'http://localhost:%d' % port
        out_dir = os.path.join(ROOT, 'bench', 'out')
        os.makedirs(out_dir, exist_ok=True)
        self.log = os.path.join(out_dir, log_name)
        self.proc = subprocess.Popen(['roslaunch', '-p', str(port), 'car'] + launch_args,
                                     stdout=open(self.log, 'w'), stderr=subprocess.STDOUT, start_new_session=True)
        import rosgraph
        master = rosgraph.Master('/faults')
        deadline = time.time() + 300
        while True:
            try:
                self.pid = xmlrpc.client.ServerProxy(master.lookupNode('/gazebo')).getPid('/faults')[2]
                break
            except Exception:
                if time.time() > deadline or self.proc.poll() is not None:
                    sys.exit('faults: sim_node did not come up; see %s' % self.log)
                time.sleep(0.5)
        import rospy
        rospy.init_node('faults', disable_signals=True)
        rospy.wait_for_service('/gazebo/get_world_properties', timeout=300)

    def alive(self):
        return os.path.exists('/proc/%d' % self.pid)

    def stop(self):
        os.killpg(self.proc.pid, signal.SIGINT)
        try:
            self.proc.wait(timeout=30)
        except subprocess.TimeoutExpired:
            os.killpg(self.proc.pid, signal.SIGKILL)


def clock_advances(within_wall=30.0):
    """True when /clock moves forward within the wall time given."""
    import rospy
    from rosgraph_msgs.msg import Clock
    t0 = rospy.wait_for_message('/clock', Clock, timeout=within_wall).clock.to_sec()
    deadline = time.time() + within_wall
    while time.time() < deadline:
        if rospy.wait_for_message('/clock', Clock, timeout=within_wall).clock.to_sec() > t0:
            return True
    return False


def spawn_delete(args):
    import rospy
    from gazebo_msgs.srv import DeleteModel, SpawnModel
    from geometry_msgs.msg import Pose
    sim = Sim(['empty_world.launch', 'gui:=false', 'rtf:=0'], 'faults_spawn_delete.log')
    try:
        xml = open(os.path.join(ROOT, 'urdf', 'demo.urdf')).read()
        spawn = rospy.ServiceProxy('/gazebo/spawn_urdf_model', SpawnModel, persistent=True)
        delete = rospy.ServiceProxy('/gazebo/delete_model', DeleteModel, persistent=True)
        pose = Pose()
        pose.position.z = 0.5
        pose.orientation.w = 1.0
        rss_warm = None
        failures = 0
        t0 = time.time()
        for i in range(args.cycles):
            ok = spawn('cycler', xml, '', pose, 'world').success and delete('cycler').success
            failures += not ok
            if i + 1 == min(1000, args.cycles):
                rss_warm = rss_mb(sim.pid)
                print('faults: spawn-delete: RSS %.1f MB after %d cycles' % (rss_warm, i + 1), flush=True)
        rss_end = rss_mb(sim.pid)
        wall = time.time() - t0
        print('faults: spawn-delete: %d cycles in %.0f wall s, %d failed; RSS %.1f MB after the first 1000, %.1f MB '
              'at the end (%+.1f MB)' % (args.cycles, wall, failures, rss_warm, rss_end, rss_end - rss_warm))
        print('faults: spawn-delete: /clock still advances: %s' % clock_advances())
    finally:
        sim.stop()


def services(args):
    import rospy
    from gazebo_msgs.srv import GetLinkState, GetModelState, GetPhysicsProperties, GetWorldProperties
    sim = Sim(['sim.launch', 'rtf:=0'], 'faults_services.log')
    try:
        rospy.wait_for_service('/gazebo/get_model_state', timeout=300)
        calls = [('/gazebo/get_world_properties', GetWorldProperties, ()),
                 ('/gazebo/get_model_state', GetModelState, ('mycar', 'world')),
                 ('/gazebo/get_physics_properties', GetPhysicsProperties, ()),
                 ('/gazebo/get_link_state', GetLinkState, ('mycar::base_link', 'world'))]
        answered = [0]
        failed = []
        slowest = [0.0]
        lock = threading.Lock()
        start = threading.Barrier(args.threads)

        def worker(k):
            start.wait()
            for j in range(args.calls // args.threads):
                name, srv, req = calls[(k + j) % len(calls)]
                t = time.time()
                try:
                    rospy.ServiceProxy(name, srv)(*req)
                    with lock:
                        answered[0] += 1
                        slowest[0] = max(slowest[0], time.time() - t)
                except Exception as e:  # noqa: BLE001 - every failure is counted and shown
                    with lock:
                        failed.append('%s: %s' % (name, e))

        threads = [threading.Thread(target=worker, args=(k,)) for k in range(args.threads)]
        t0 = time.time()
        for t in threads:
            t.start()
        for t in threads:
            t.join()
        print('faults: services: %d calls from %d threads in %.1f wall s: %d answered, %d failed, slowest %.2f s' %
              (args.calls // args.threads * args.threads, args.threads, time.time() - t0, answered[0], len(failed),
               slowest[0]))
        for f in failed[:5]:
            print('faults: services: failed: %s' % f)
        print('faults: services: sim_node still running: %s; /clock still advances: %s' %
              (sim.alive(), clock_advances()))
    finally:
        sim.stop()


def cmd_vel(args):
    import rospy
    from geometry_msgs.msg import Twist
    sim = Sim(['sim.launch', 'rtf:=1'], 'faults_cmd_vel.log')
    try:
        pub = rospy.Publisher('/cmd_vel', Twist, queue_size=1)
        deadline = time.time() + 30
        while pub.get_num_connections() == 0 and time.time() < deadline:
            time.sleep(0.05)
        msg = Twist()
        msg.linear.x = 0.5
        msg.angular.z = 0.5
        period = 1.0 / args.rate
        sent = 0
        sim0, wall0 = rospy.get_rostime().to_sec(), time.time()
        next_t = wall0
        while time.time() - wall0 < args.seconds:
            pub.publish(msg)
            sent += 1
            next_t += period
            lag = next_t - time.time()
            if lag > 0:
                time.sleep(lag)
        wall = time.time() - wall0
        sim_s = rospy.get_rostime().to_sec() - sim0
        print('faults: cmd-vel: %d messages in %.1f wall s (%.0f Hz, asked %d Hz); sim time %.2f s: real-time '
              'factor %.3f; sim_node still running: %s' %
              (sent, wall, sent / wall, args.rate, sim_s, sim_s / wall, sim.alive()))
    finally:
        sim.stop()


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    sub = ap.add_subparsers(dest='what', required=True)
    a = sub.add_parser('spawn-delete')
    a.add_argument('--cycles', type=int, default=10000)
    a = sub.add_parser('services')
    a.add_argument('--calls', type=int, default=1000)
    a.add_argument('--threads', type=int, default=50)
    a = sub.add_parser('cmd-vel')
    a.add_argument('--rate', type=float, default=10000.0)
    a.add_argument('--seconds', type=float, default=60.0)
    args = ap.parse_args()
    {'spawn-delete': spawn_delete, 'services': services, 'cmd-vel': cmd_vel}[args.what](args)


if __name__ == '__main__':
    main()
