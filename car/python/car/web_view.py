"""A live 3-D web view of a simulation, served by viser (its own three.js client over WebSockets).

WebScene draws and drives; where its data comes from is the caller's business:
- the ROS node `web_view` (car.ros.web_view_node) feeds it from /tf, /scan, the depth cloud, the camera image, /clock
  and /gazebo/model_states, and its drive panel publishes cmd_vel;
- `car.web_view.view(world)` attaches it to a car._core.World stepped from Python (call view.update() after steps;
  view.step(n) does both).

What it shows, in the fixed frame (`odom`, the simulator's world frame, REP 105): the world's visuals from the SDF in
their materials' colours (boxes, cylinders, spheres, planes, meshes), every robot's URDF visuals posed link by
link, the lidar scan as points, the depth cloud thinned to at most `cloud_budget` points by a regular stride, the
camera image in the side panel, each robot's odometry trail, sim time and the real-time factor. The drive panel
(per robot) sets (v, w) for `hold` seconds per click — a dead-man timeout: without another click the robot
stops —, pauses, unpauses and resets.
"""
from __future__ import annotations

import math
import os
import threading
import time

import numpy as np

from car import materials
from car.world_geometry import transform

PLANE_SIZE = 40.0  # [m] planes are drawn as this square, 1 mm thick, top face on the plane
PLACEHOLDER_SIZE = 0.1  # [m] edge of the wireframe cube drawn where a visual mesh file is missing
SCAN_COLOUR = (255, 0, 255)  # lidar points: magenta, a colour no material of the seed world or car has
# the odometry trail: green, apart from the seed car's orange and the scan's magenta
TRAIL_COLOUR = (40, 190, 90)


def _rgb(rgba):
    return tuple(int(round(255 * max(0.0, min(1.0, c)))) for c in rgba[:3])


def wxyz(R):
    """(w, x, y, z) of a 3x3 rotation matrix."""
    R = np.asarray(R, dtype=float)
    w = math.sqrt(max(0.0, 1.0 + R[0, 0] + R[1, 1] + R[2, 2])) / 2.0
    x = math.copysign(math.sqrt(max(0.0, 1.0 + R[0, 0] - R[1, 1] - R[2, 2])) / 2.0, R[2, 1] - R[1, 2])
    y = math.copysign(math.sqrt(max(0.0, 1.0 - R[0, 0] + R[1, 1] - R[2, 2])) / 2.0, R[0, 2] - R[2, 0])
    z = math.copysign(math.sqrt(max(0.0, 1.0 - R[0, 0] - R[1, 1] + R[2, 2])) / 2.0, R[1, 0] - R[0, 1])
    return (w, x, y, z)


def thin(points, budget):
    """At most `budget` rows of an (N, k) array, by a regular stride (deterministic, keeps the cloud's shape)."""
    n = len(points)
    if n <= budget:
        return points
    return points[::int(math.ceil(n / budget))]


class WebScene:
    """The viser server, the scene graph and the side panel."""

    def __init__(self, host='127.0.0.1', port=8080, cloud_budget=20000, hold=1.0, trail_points=2000):
        import viser
        self.server = viser.ViserServer(host=host, port=port, verbose=False)
        self.host, self.port = host, self.server.get_port()
        self.cloud_budget, self.hold, self.trail_points = cloud_budget, hold, trail_points
        self.scene, self.gui = self.server.scene, self.server.gui
        self.scene.set_up_direction('+z')
        self.scene.add_light_directional('/sun', intensity=1.5, wxyz=wxyz(_look_down()))
        self.scene.add_light_ambient('/ambient', intensity=0.8)
        self._frames = {}
        self._trails = {}
        self._lock = threading.Lock()
        self._drive = {}          # robot -> (v, w, until [wall s])
        self.on_cmd = None        # f(robot, v, w)
        self.on_pause = None      # f(paused: bool)
        self.on_reset = None      # f()
        self._build_panel()

    @property
    def url(self):
        return 'http://%s:%d' % (self.host, self.port)

    # ---- panel ----
    def _build_panel(self):
        g = self.gui
        self.status = g.add_markdown('**sim time** – · **real-time factor** –')
        self.robot_select = g.add_dropdown('robot', ['(none)'])
        self.speed = g.add_slider('speed [m/s]', 0.05, 2.0, 0.05, 0.5)
        self.turn = g.add_slider('turn [rad/s]', 0.1, 3.0, 0.1, 1.0)
        for label, (fv, fw) in (('Forward', (1, 0)), ('Back', (-1, 0)), ('Left', (0, 1)), ('Right', (0, -1)),
                                ('Stop', (0, 0))):
            b = g.add_button(label)
            b.on_click(lambda _e, fv=fv, fw=fw: self.press(fv * self.speed.value, fw * self.turn.value,
                                                          hold=0.0 if fv == fw == 0 else self.hold))
        pause, unpause, reset = g.add_button('Pause'), g.add_button('Unpause'), g.add_button('Reset world')
        pause.on_click(lambda _e: self.on_pause and self.on_pause(True))
        unpause.on_click(lambda _e: self.on_pause and self.on_pause(False))
        reset.on_click(lambda _e: self._reset())
        self.image = None

    def _reset(self):
        with self._lock:
            for t in self._trails.values():
                t.clear()
        if self.on_reset:
            self.on_reset()

    def press(self, v, w, hold=None, robot=None):
        """Drive the selected robot (or `robot`) at (v, w) for `hold` seconds (the dead-man window)."""
        robot = robot or self.robot_select.value
        if robot == '(none)':
            return
        with self._lock:
            self._drive[robot] = (v, w, time.monotonic() + (self.hold if hold is None else hold))
        if self.on_cmd:
            self.on_cmd(robot, v, w)

    def commands(self):
        """(robot, v, w) for every robot with a live command, and one (robot, 0, 0) when its window closes."""
        now = time.monotonic()
        out = []
        with self._lock:
            for robot, (v, w, until) in list(self._drive.items()):
                if now < until:
                    out.append((robot, v, w))
                else:
                    out.append((robot, 0.0, 0.0))
                    del self._drive[robot]
        return out

    def set_status(self, sim_time, rtf):
        self.status.content = '**sim time** %.2f s · **real-time factor** %s' % (
            sim_time, '–' if rtf is None else '%.2f' % rtf)

    def set_image(self, rgb):
        """The camera's colour image (H, W, 3) uint8 in the side panel."""
        if self.image is None:
            self.image = self.gui.add_image(rgb, label='camera', format='jpeg', jpeg_quality=80)
        else:
            self.image.image = rgb

    # ---- scene ----
    def _add_shape(self, name, s, colour, base_dir=''):
        """One visual (a core shape dict) as a child node `name`; None for what it cannot draw."""
        T = transform(s['origin']) if 'origin' in s else np.eye(4)
        kw = dict(position=tuple(T[:3, 3]), wxyz=wxyz(T[:3, :3]))
        c = _rgb(colour)
        t = s['type']
        if t == 'box':
            return self.scene.add_box(name, color=c, dimensions=tuple(s['size']), **kw)
        if t == 'cylinder':
            return self.scene.add_cylinder(name, radius=s['radius'], height=s['length'], color=c, **kw)
        if t == 'sphere':
            return self.scene.add_icosphere(name, radius=s['radius'], color=c, **kw)
        if t == 'plane':
            return self.scene.add_box(name, color=c, dimensions=(PLANE_SIZE, PLANE_SIZE, 0.001),
                                      position=(T[0, 3], T[1, 3], T[2, 3] - 0.0005), wxyz=kw['wxyz'])
        if t == 'mesh':
            path = s.get('path') or ''
            if not path:
                from car import _core
                path = _core.resolve_uri(s.get('uri') or s.get('filename') or '', base_dir) or ''
            if path and os.path.isfile(path):
                import trimesh
                try:
                    mesh = trimesh.load(path, force='mesh')
                    mesh.visual = trimesh.visual.ColorVisuals(mesh, face_colors=list(c) + [255])
                    return self.scene.add_mesh_trimesh(name, mesh, scale=tuple(s.get('scale', (1, 1, 1))), **kw)
                except Exception:  # unreadable: the placeholder below, as for a missing file
                    pass
            # a visual mesh that is missing (the core warned when it loaded the robot): a wireframe cube in its
            # place, so the link still shows where it is
            return self.scene.add_box(name, color=c, dimensions=(PLACEHOLDER_SIZE,) * 3, wireframe=True, **kw)
        return None

    def add_world(self, desc):
        """Every model of a world description (car._core.load_world_file) under /world/<model>."""
        base = os.path.dirname(desc.get('source') or '')
        for m in desc['models']:
            Tm = transform(m['pose'])
            self._frames[('world', m['name'])] = self.scene.add_frame(
                '/world/%s' % m['name'], show_axes=False, position=tuple(Tm[:3, 3]), wxyz=wxyz(Tm[:3, :3]))
            for li, l in enumerate(m['links']):
                Tl = transform(l['pose'])
                self.scene.add_frame('/world/%s/%d' % (m['name'], li), show_axes=False, position=tuple(Tl[:3, 3]),
                                     wxyz=wxyz(Tl[:3, :3]))
                for vi, v in enumerate(l['visuals']):
                    self._add_shape('/world/%s/%d/%d' % (m['name'], li, vi), v, materials.visual_colour(v), base)

    def set_model_pose(self, model, T):
        f = self._frames.get(('world', model))
        if f is not None:
            f.position, f.wxyz = tuple(T[:3, 3]), wxyz(T[:3, :3])

    def add_robot(self, name, urdf_text, base_dir=''):
        """A robot from URDF text: one frame per link, its visuals inside, coloured by the core's rule."""
        from car import _core
        model = _core.load_urdf_string(urdf_text, name)
        colours = _core.link_colours(urdf_text, base_dir)
        for l in model['links']:
            frame = self.scene.add_frame('/robots/%s/%s' % (name, l['name']), show_axes=False, visible=False)
            self._frames[(name, l['name'])] = frame
            for vi, v in enumerate(l['visuals']):
                self._add_shape('/robots/%s/%s/%d' % (name, l['name'], vi), v['shape'], colours[l['name']], base_dir)
        with self._lock:
            self._trails.setdefault(name, [])
        opts = [r for r in self.robot_select.options if r != '(none)'] + [name]
        self.robot_select.options = opts
        self.robot_select.value = opts[0]

    def set_link_pose(self, robot, link, T):
        f = self._frames.get((robot, link))
        if f is not None:
            f.position, f.wxyz = tuple(T[:3, 3]), wxyz(T[:3, :3])
            f.visible = True

    def add_trail_point(self, robot, xy):
        """Appends to the robot's odometry trail when it moved more than 1 cm."""
        with self._lock:
            trail = self._trails.setdefault(robot, [])
            if trail and math.hypot(xy[0] - trail[-1][0], xy[1] - trail[-1][1]) < 0.01:
                return
            trail.append((xy[0], xy[1]))
            del trail[:-self.trail_points]
            pts = list(trail)
        if len(pts) >= 2:
            seg = np.array([[[a[0], a[1], 0.005], [b[0], b[1], 0.005]] for a, b in zip(pts[:-1], pts[1:])],
                           dtype=np.float32)
            self.scene.add_line_segments('/trails/%s' % robot, seg, TRAIL_COLOUR, thickness=0.02)

    def set_scan(self, robot, points):
        """Lidar hits (N, 3) [m] in the fixed frame."""
        pts = np.asarray(points, dtype=np.float32).reshape(-1, 3)
        self.scene.add_point_cloud('/scans/%s' % robot, pts, SCAN_COLOUR, point_size=0.04, point_shape='circle')

    def set_cloud(self, robot, points, colours=None):
        """A depth cloud (N, 3) [m] in the fixed frame, thinned to the budget; colours (N, 3) uint8 or one."""
        pts = np.asarray(points, dtype=np.float32).reshape(-1, 3)
        keep = np.isfinite(pts).all(axis=1)
        pts = pts[keep]
        col = (90, 160, 255) if colours is None else np.asarray(colours, np.uint8).reshape(-1, 3)[keep]
        idx = thin(np.arange(len(pts)), self.cloud_budget)
        col = col if isinstance(col, tuple) else col[idx]
        self.scene.add_point_cloud('/clouds/%s' % robot, pts[idx], col, point_size=0.015)

    def look_from(self, position, look_at, fov_deg=None, up=(0.0, 0.0, 1.0)):
        """The camera every new browser starts with (fixed frame [m]; up: the image's up direction; looking
        straight down, give a horizontal one, e.g. (0, 1, 0) puts +y up and +x right)."""
        cam = self.server.initial_camera
        cam.position, cam.look_at, cam.up = tuple(position), tuple(look_at), tuple(up)
        if fov_deg:
            cam.fov = math.radians(fov_deg)

    def has_clients(self):
        """Whether a browser is connected now."""
        return len(self.server.get_clients()) > 0

    def stop(self):
        self.server.stop()


def _look_down():
    # a sun from above and a little to the side
    a = math.radians(30)
    return np.array([[1, 0, 0], [0, math.cos(a), -math.sin(a)], [0, math.sin(a), math.cos(a)]])


class WorldView:
    """A WebScene on a car._core.World stepped from Python (see view())."""

    def __init__(self, world, world_file=None, **kw):
        from car import _core
        self.world = world
        self.web = WebScene(**kw)
        if world_file:
            self.web.add_world(_core.load_world_file(world_file))
        self._robots = {}
        self.web.on_cmd = lambda robot, v, w: self.world.set_cmd_vel(robot, v, w)
        self.web.on_reset = self.world.reset
        self._paused = False
        self.web.on_pause = lambda p: setattr(self, '_paused', p)
        self._last = (time.monotonic(), world.time)

    def add_robot(self, name, urdf_text):
        from car import _core
        model = _core.load_urdf_string(urdf_text, name)
        self._robots[name] = [l['name'] for l in model['links']]
        self.web.add_robot(name, urdf_text)

    def update(self):
        """Poses, trails, status and commands from/to the world (call it from the thread that steps the world)."""
        for robot, v, w in self.web.commands():
            self.world.set_cmd_vel(robot, v, w)
        for robot, links in self._robots.items():
            for link in links:
                p = self.world.link_pose(robot, link)
                T = np.eye(4)
                T[:3, 3] = p['position']
                x, y, z, w = p['orientation']
                T[:3, :3] = _rot(x, y, z, w)
                self.web.set_link_pose(robot, link, T)
            ms = self.world.model_state(robot)
            self.web.add_trail_point(robot, ms['position'][:2])
        now, t = time.monotonic(), self.world.time
        dt_wall = now - self._last[0]
        rtf = (t - self._last[1]) / dt_wall if dt_wall > 0 else None
        self._last = (now, t)
        self.web.set_status(t, rtf)

    def step(self, n=1):
        """Steps the world (unless paused from the browser) and updates the view."""
        if not self._paused:
            self.world.step(n)
        self.update()


def _rot(x, y, z, w):
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                     [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                     [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])


def view(world, world_file=None, robots=None, host='127.0.0.1', port=8080, **kw):
    """Attaches a web view to a car._core.World: robots maps robot name -> URDF text (those to draw). Returns a
    WorldView; call .update() after stepping, or step with .step(n). Prints the URL."""
    v = WorldView(world, world_file, host=host, port=port, **kw)
    for name, text in (robots or {}).items():
        v.add_robot(name, text)
    print('car web view: %s' % v.web.url)
    return v


def _pose_matrix(p):
    """4x4 from a core pose dict {'xyz', 'rpy'} (URDF's fixed-axis roll, pitch, yaw)."""
    r, pch, y = p['rpy']
    cr, sr, cp, sp, cy, sy = math.cos(r), math.sin(r), math.cos(pch), math.sin(pch), math.cos(y), math.sin(y)
    T = np.eye(4)
    T[:3, :3] = [[cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
                 [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
                 [-sp, cp * sr, cp * cr]]
    T[:3, 3] = p['xyz']
    return T


def links_at_zero(model):
    """Each link's pose in the root link's frame with every joint at zero: {link: 4x4}."""
    out = {model['links'][0]['name']: np.eye(4)} if model['links'] else {}
    joints = list(model['joints'])
    while joints:
        rest = [j for j in joints if j['parent'] not in out]
        for j in joints:
            if j['parent'] in out:
                out[j['child']] = out[j['parent']] @ _pose_matrix(j['origin'])
        if len(rest) == len(joints):
            break
        joints = rest
    return out


class Replay:
    """car batch runs replayed in a WebScene from OUTDIR/trajectories.parquet: the scenario's world, every run's
    trail, and each robot drawn rigidly at its recorded base pose (x, y, yaw; joints at zero; z as spawned)."""

    def __init__(self, outdir, scenario_file, runs=None, **kw):
        import pyarrow.parquet as pq
        from car import _core, scenario
        from car.batch_run import _model_text
        self.web = WebScene(**kw)
        table = pq.read_table(os.path.join(outdir, 'trajectories.parquet')).to_pydict()
        scenarios = scenario.load(scenario_file)
        self.runs = sorted(set(table['run'])) if runs is None else list(runs)
        # runs are car batch's run ids; a sweep shares the first scenario's world and robot models
        first = scenarios[0]['scenario']
        if first.get('world'):
            self.web.add_world(_core.load_world_file(first['world']))
        # one drawn robot per scenario robot (runs share the model), and every run's path as a trail
        self.robots = {}
        for r in first['robots']:
            text = _model_text(r)
            model = _core.load_urdf_string(text, r['name'])
            self.web.add_robot(r['name'], text)
            self.robots[r['name']] = (links_at_zero(model), r['pose']['z'])
        self.samples = {}  # (run, robot) -> [(t, x, y, yaw)]
        for run, robot, t, x, y, yaw in zip(table['run'], table['robot'], table['t'], table['x'], table['y'],
                                            table['yaw']):
            if run in self.runs:
                self.samples.setdefault((run, robot), []).append((t, x, y, yaw))
        for (run, robot), s in self.samples.items():
            s.sort()
            seg = np.array([[[a[1], a[2], 0.005], [b[1], b[2], 0.005]] for a, b in zip(s[:-1], s[1:])], np.float32)
            if len(seg):
                self.web.scene.add_line_segments('/replay/%s/%s' % (run, robot), seg, (230, 80, 20), thickness=0.01)

    def show(self, run, t):
        """Poses the robots of `run` at sim time t [s] (the last sample at or before t)."""
        for robot, (links, z) in self.robots.items():
            s = self.samples.get((run, robot))
            if not s:
                continue
            i = max(0, np.searchsorted([p[0] for p in s], t, side='right') - 1)
            _, x, y, yaw = s[i]
            base = np.eye(4)
            base[:3, :3] = [[math.cos(yaw), -math.sin(yaw), 0], [math.sin(yaw), math.cos(yaw), 0], [0, 0, 1]]
            base[:3, 3] = (x, y, z)
            for link, T in links.items():
                self.web.set_link_pose(robot, link, base @ T)
        self.web.set_status(t, None)

    def play(self, speed=1.0, loop=False):
        """Plays every run after the other at `speed` x real time (wall clock: this is a viewer)."""
        while True:
            for run in self.runs:
                end = max(p[0] for (r, _), s in self.samples.items() if r == run for p in s)
                t0 = time.monotonic()
                t = 0.0
                while t <= end:
                    self.show(run, t)
                    time.sleep(0.05)
                    t = (time.monotonic() - t0) * speed
            if not loop:
                return
