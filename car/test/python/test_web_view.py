"""car.web_view without a browser: the scene graph it builds (viser's server-side handles), the drive panel's
dead-man window, and the replay of car batch runs. The browser itself is tested in test/ros/web_view.test."""
import math
import os
import time

import numpy as np
import pytest

from conftest import DATA
from car import batch, scenario
from car import web_view

BATCH = os.path.join(DATA, 'batch')


def test_thin_keeps_at_most_the_budget_by_a_regular_stride():
    pts = np.arange(100000).reshape(-1, 1)
    out = web_view.thin(pts, 20000)
    assert len(out) == 20000          # stride ceil(100000 / 20000) = 5
    assert out[1, 0] - out[0, 0] == 5


def test_wxyz_of_a_quarter_turn_about_z():
    c, s = math.cos(math.pi / 2), math.sin(math.pi / 2)
    w, x, y, z = web_view.wxyz([[c, -s, 0], [s, c, 0], [0, 0, 1]])
    assert (w, x, y, z) == pytest.approx((math.sqrt(0.5), 0.0, 0.0, math.sqrt(0.5)))


def test_links_at_zero_compose_the_joint_origins():
    model = {'links': [{'name': 'a'}, {'name': 'b'}, {'name': 'c'}],
             'joints': [{'parent': 'b', 'child': 'c', 'origin': {'xyz': [1, 0, 0], 'rpy': [0, 0, 0]}},
                        {'parent': 'a', 'child': 'b', 'origin': {'xyz': [0, 0, 1], 'rpy': [0, 0, math.pi / 2]}}]}
    T = web_view.links_at_zero(model)
    # c sits 1 m along b's x, which a's quarter turn points along a's y: (0, 1, 1)
    assert T['c'][:3, 3] == pytest.approx([0.0, 1.0, 1.0])


@pytest.fixture()
def scene():
    s = web_view.WebScene(port=0)
    yield s
    s.stop()


class FakeClock:
    """web_view's `time` module with a monotonic() the test sets: the dead-man window is judged against it, not
    against how fast this process happens to run (everything else passes through to the real module)."""

    def __init__(self, now=1000.0):
        self.now = now

    def monotonic(self):
        return self.now

    def __getattr__(self, name):
        return getattr(time, name)


def test_dead_man_window_sends_the_command_then_one_stop(scene, monkeypatch):
    clock = FakeClock()
    monkeypatch.setattr(web_view, 'time', clock)
    scene.add_robot('r', '<robot name="r"><link name="base"><inertial><mass value="1"/>'
                         '<inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial></link></robot>')
    sent = []
    scene.on_cmd = lambda robot, v, w: sent.append((robot, v, w))
    scene.press(0.5, 0.0, hold=0.25)
    assert sent == [('r', 0.5, 0.0)]
    clock.now += 0.25 - 2 ** -10                      # (binary fractions: the window's end is exact)
    assert scene.commands() == [('r', 0.5, 0.0)]      # inside the window: the command again
    clock.now += 2 ** -10
    assert scene.commands() == [('r', 0.0, 0.0)]      # the window closed at press + hold: one stop
    assert scene.commands() == []                     # and then nothing


def test_missing_visual_mesh_is_drawn_as_a_wireframe_cube(scene):
    # issue 29 item 3: the robot still shows where its link is; the cube has the placeholder's edge
    with open(os.path.join(DATA, 'meshes', 'visual_mesh_missing.urdf')) as f:
        scene.add_robot('r', f.read(), base_dir=os.path.join(DATA, 'meshes'))
    h = scene.server.scene.get_handle_by_name('/robots/r/base_link/0')
    assert h.wireframe is True
    assert tuple(h.dimensions) == (web_view.PLACEHOLDER_SIZE,) * 3


def test_replay_poses_the_robot_at_its_recorded_base_pose(tmp_path):
    path = os.path.join(BATCH, 'straight.yaml')
    results = batch.run_all(scenario.load(path)[:1], str(tmp_path), serial=True, progress=False)
    batch.write_parquet(results, str(tmp_path))
    r = web_view.Replay(str(tmp_path), path, port=0)
    try:
        run = r.runs[0]
        t, x, y, yaw = r.samples[(run, 'mycar')][-1]
        r.show(run, t + 1.0)  # after the last sample: the last pose
        root = next(iter(r.robots['mycar'][0]))
        f = r.web._frames[('mycar', root)]
        assert tuple(f.position) == pytest.approx((x, y, 0.0))
        # the first run drives 0.5 m/s for 2 s (less the 0.06 m ramp; a turn after 1.5 s shortens x a little)
        assert 0.85 < x < 0.94
        assert tuple(f.wxyz) == pytest.approx((math.cos(yaw / 2), 0.0, 0.0, math.sin(yaw / 2)), abs=1e-9)
    finally:
        r.web.stop()
