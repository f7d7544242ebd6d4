"""Soak: sim_node's resident memory (RSS) over a long run in sim time.

Starts `roslaunch car sim.launch rtf:=0` (--rtf) on a free port, subscribes to /scan and /camera/depth/points (so the
lazy laser and Kinect compute every frame), and, from the car's first scan and cloud on, samples VmRSS of the
simulator process every --every sim seconds until --sim-seconds of sim time (or --max-wall wall seconds, then the rate is extrapolated and the report says so).
The growth per sim hour is the slope of a least-squares line through the samples after --warmup sim seconds; the
report also gives RSS first / last / min / max after the warm-up (issue 51: flat within 5 MB) and the warnings and
errors the simulator node logged, counted in rosout.log of a log folder of the run's own (ROS_LOG_DIR).
Samples go to bench/out/soak.csv, the run's ROS logs to bench/out/soak_logs/."""
import argparse
import os
import shutil
import signal
import socket
import subprocess
import sys
import time
import xmlrpc.client

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def free_port():
    with socket.socket() as s:
        s.bind(('localhost', 0))
        return s.getsockname()[1]


def rss_mb(pid):
    """Resident set size of a process [MB], from /proc."""
    with open('/proc/%d/status' % pid) as f:
        for line in f:
            if line.startswith('VmRSS:'):
                return int(line.split()[1]) / 1024.0
    raise RuntimeError('no VmRSS for pid %d' % pid)


def node_warnings(log_dir, after, node='/gazebo'):
    """Lines of rosout.log under log_dir (symbolic links, such as `latest`, not followed) that `node` logged at WARN
    or above: (count stamped up to sim time `after` [s], count stamped later, the later ones' first few lines).
    rosout.log's lines read `STAMP LEVEL /node [file:line(function)] [topics: ...] text`; STAMP is sim time."""
    before, later = 0, []
    for d, _, files in os.walk(log_dir):
        if 'rosout.log' in files:
            with open(os.path.join(d, 'rosout.log'), errors='replace') as f:
                for line in f:
                    parts = line.split(None, 3)
                    if len(parts) >= 3 and parts[2] == node and parts[1] in ('WARN', 'ERROR', 'FATAL'):
                        if float(parts[0]) <= after:
                            before += 1
                        else:
                            later.append(line.rstrip())
    return before, len(later), later[:5]


def slope(xs, ys):
    n = len(xs)
    mx, my = sum(xs) / n, sum(ys) / n
    sxx = sum((x - mx) ** 2 for x in xs)
    return sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sxx if sxx > 0 else 0.0


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument('--sim-seconds', type=float, default=3600.0, help='sim time to run [s]')
    ap.add_argument('--every', type=float, default=30.0, help='sample period [sim s]')
    ap.add_argument('--warmup', type=float, default=60.0, help='sim time left out of the fit [s]')
    ap.add_argument('--max-wall', type=float, default=0.0, help='stop after this many wall seconds (0 = never)')
    ap.add_argument('--rtf', default='0', help='sim.launch\'s real-time factor (default 0: as fast as possible)')
    ap.add_argument('--no-cloud', dest='cloud', action='store_false',
                    help='subscribe to /scan only (a control: the Kinect computes nothing, 10 MB clouds queue nowhere)')
    args = ap.parse_args()

    # a stop (SIGTERM; a background job ignores SIGINT) still shuts roslaunch down, in the finally below
    signal.signal(signal.SIGTERM, lambda *_: sys.exit('soak: stopped by SIGTERM'))
    port = free_port()
    os.environ['ROS_MASTER_URI'] = 'http://localhost:%d' % port
    out_dir = os.path.join(ROOT, 'bench', 'out')
    os.makedirs(out_dir, exist_ok=True)
    # this run's own log folder, so rosout.log holds only this run's lines
    log_dir = os.path.join(out_dir, 'soak_logs')
    shutil.rmtree(log_dir, ignore_errors=True)
    os.environ['ROS_LOG_DIR'] = log_dir
    launch_log = open(os.path.join(out_dir, 'soak_roslaunch.log'), 'w')
    launch = subprocess.Popen(['roslaunch', '-p', str(port), 'car', 'sim.launch', 'rtf:=' + args.rtf],
                              stdout=launch_log, stderr=subprocess.STDOUT, start_new_session=True)
    try:
        import rosgraph
        import rospy
        from sensor_msgs.msg import LaserScan, PointCloud2

        master = rosgraph.Master('/soak')
        deadline = time.time() + 300
        while True:  # the simulator's node, then its pid through its own XML-RPC API
            try:
                pid = xmlrpc.client.ServerProxy(master.lookupNode('/gazebo')).getPid('/soak')[2]
                break
            except Exception:
                if time.time() > deadline or launch.poll() is not None:
                    sys.exit('soak: sim_node did not come up; see bench/out/soak_roslaunch.log')
                time.sleep(0.5)
        rospy.init_node('soak', disable_signals=True)
        counts = {'scan': 0, 'cloud': 0}
        rospy.Subscriber('/scan', LaserScan, lambda m: counts.__setitem__('scan', counts['scan'] + 1), queue_size=1)
        if args.cloud:
            rospy.Subscriber('/camera/depth/points', PointCloud2,
                             lambda m: counts.__setitem__('cloud', counts['cloud'] + 1), queue_size=1,
                             buff_size=1 << 25)
        # the run starts when the car is in the world and both sensors publish: at rtf 0 the empty world runs far
        # ahead while the spawn is still being prepared (2 000 sim s under load), which is no soak of the car
        deadline = time.time() + 600
        while counts['scan'] == 0 or (args.cloud and counts['cloud'] == 0):
            if time.time() > deadline or launch.poll() is not None:
                sys.exit('soak: no /scan and cloud within 600 s of wall time (scans %d, clouds %d); see '
                         'bench/out/soak_roslaunch.log' % (counts['scan'], counts['cloud']))
            time.sleep(0.1)
        t_start = rospy.get_rostime().to_sec()
        print('soak: the car publishes %s from sim %.1f s; sim seconds below count from there'
              % ('/scan and the cloud' if args.cloud else '/scan', t_start), flush=True)
        samples = []
        wall0 = time.time()
        next_t = 0.0
        csv = open(os.path.join(out_dir, 'soak.csv'), 'w')
        csv.write('sim_s,wall_s,rss_mb,scans,clouds\n')
        truncated = False
        while True:
            t = rospy.get_rostime().to_sec() - t_start
            if t >= next_t:
                r = rss_mb(pid)
                samples.append((t, r))
                csv.write('%.3f,%.1f,%.2f,%d,%d\n' % (t, time.time() - wall0, r, counts['scan'], counts['cloud']))
                csv.flush()
                print('soak: sim %7.1f s  wall %6.0f s  RSS %7.2f MB  scans %d  clouds %d' %
                      (t, time.time() - wall0, r, counts['scan'], counts['cloud']), flush=True)
                next_t = (int(t / args.every) + 1) * args.every
            if t >= args.sim_seconds:
                break
            if args.max_wall and time.time() - wall0 > args.max_wall:
                truncated = True
                break
            if launch.poll() is not None:
                sys.exit('soak: roslaunch ended early; see bench/out/soak_roslaunch.log')
            time.sleep(0.2)
        wall = time.time() - wall0
        fit = [(t, r) for t, r in samples if t >= args.warmup]
        if len(fit) < 2:
            sys.exit('soak: fewer than two samples after the warm-up; run longer')
        per_hour = slope([t for t, _ in fit], [r for _, r in fit]) * 3600.0
        t_end = samples[-1][0]
        print('soak: %.0f sim s in %.0f wall s (real-time factor %.2f), /scan %d msgs, cloud %d msgs' %
              (t_end, wall, t_end / wall, counts['scan'], counts['cloud']))
        print('soak: sim_node RSS %.1f MB at %.0f sim s, %.1f MB at %.0f sim s; least-squares growth %+.2f MB per '
              'sim hour (samples after %.0f sim s)%s' %
              (fit[0][1], fit[0][0], fit[-1][1], fit[-1][0], per_hour, args.warmup,
               '; stopped at the wall limit, so the rate is extrapolated from %.0f sim s' % t_end if truncated else ''))
        rss = [r for _, r in fit]
        print('soak: RSS after the warm-up: first %.1f MB, last %.1f MB, min %.1f MB, max %.1f MB: spread %.1f MB '
              'over %d samples' % (rss[0], rss[-1], min(rss), max(rss), max(rss) - min(rss), len(rss)))
        # the model's load warnings (the tutorial's URDF) come with the spawn, before the first scan; the soak's own
        # question is what the node logs while it runs
        n_load, n_run, first = node_warnings(log_dir, t_start)
        print('soak: /gazebo logged %d warning(s) or error(s) up to the car\'s first scan (sim %.1f s: loading) and '
              '%d while it ran (%s)' % (n_load, t_start, n_run, os.path.join(log_dir, '*/rosout.log')))
        for line in first:
            print('soak:   ' + line)
    finally:
        os.killpg(launch.pid, signal.SIGINT)
        try:
            launch.wait(timeout=30)
        except subprocess.TimeoutExpired:
            os.killpg(launch.pid, signal.SIGKILL)


if __name__ == '__main__':
    main()
