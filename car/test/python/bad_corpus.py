"""The adversarial corpus (test/data/bad/EXPECTED.yaml) and how each entry point is run on it, bounded.

Shared by test_bad_corpus.py (check_model, world_tool check, the Python API) and test/ros/test_bad_spawn.py
(spawn_model against a running node). Every run is a subprocess under a memory limit (RLIMIT_AS) and a timeout.
"""
from __future__ import annotations

import json
import os
import resource
import subprocess
import sys

import yaml

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
BAD = os.path.join(ROOT, 'test', 'data', 'bad')
TABLE = os.path.join(BAD, 'EXPECTED.yaml')
MEMORY_LIMIT = 2 << 30   # [bytes] address space of each run
TIMEOUT = 180            # [s] per run, generous for a busy machine (the 50 MB world takes ~10 s alone, 50 s at load 6)
PASSWD_MARK = 'root:x:0:0'  # what /etc/passwd would leak through an external entity


def load_table() -> dict:
    with open(TABLE, encoding='utf-8') as f:
        return yaml.safe_load(f)


def cases(kinds=None) -> list:
    """(name, entry) pairs of the table, in its order; kinds filters by 'urdf', 'xacro', 'world'."""
    out = []
    for name, entry in load_table().items():
        kind = entry.get('kind') or name.rsplit('.', 1)[-1]
        entry = dict(entry, kind=kind)
        if kinds is None or kind in kinds:
            out.append((name, entry))
    return out


# ---- generated cases (too big to commit) ------------------------------------------------------------------

def _huge_urdf(path: str) -> None:
    """The reference robot after a 50 MB comment."""
    ref = open(os.path.join(BAD, 'reference.urdf'), encoding='utf-8').read()
    head, body = ref.split('\n', 1)
    with open(path, 'w', encoding='utf-8') as f:
        f.write(head + '\n<!-- ')
        chunk = 'padding ' * 131072  # 1 MiB
        for _ in range(50):
            f.write(chunk)
        f.write(' -->\n' + body)


def _huge_world(path: str) -> None:
    ref = open(os.path.join(BAD, 'reference.world'), encoding='utf-8').read()
    head, body = ref.split('\n', 1)
    with open(path, 'w', encoding='utf-8') as f:
        f.write(head + '\n<!-- ')
        chunk = 'padding ' * 131072
        for _ in range(50):
            f.write(chunk)
        f.write(' -->\n' + body)


def _many_models_world(path: str) -> None:
    """10 000 static boxes on a 100 x 100 grid, 2 m apart."""
    with open(path, 'w', encoding='utf-8') as f:
        f.write('<?xml version="1.0"?>\n<sdf version="1.7">\n  <world name="many">\n')
        for i in range(10000):
            f.write('    <model name="box_%d"><static>true</static><pose>%d %d 0.5 0 0 0</pose><link name="l">'
                    '<collision name="c"><geometry><box><size>1 1 1</size></box></geometry></collision>'
                    '</link></model>\n' % (i, 2 * (i % 100), 2 * (i // 100)))
        f.write('  </world>\n</sdf>\n')


GENERATORS = {'huge.urdf': _huge_urdf, 'huge.world': _huge_world, 'many_models.world': _many_models_world}


def path_of(name: str, entry: dict, tmpdir: str) -> str:
    """The case's file: in test/data/bad/, or generated into tmpdir (once)."""
    if not entry.get('generated'):
        return os.path.join(BAD, name)
    p = os.path.join(tmpdir, name)
    if not os.path.exists(p):
        GENERATORS[name](p)
    return p


# ---- bounded runs -----------------------------------------------------------------------------------------

def _limit_memory():
    # Under AddressSanitizer (tools/sanitize.sh) the address space holds ASan's shadow (terabytes, reserved, not
    # used): RLIMIT_AS would stop the program before main. sanitize.sh bounds it with hard_rss_limit_mb instead.
    if 'hard_rss_limit_mb' in os.environ.get('ASAN_OPTIONS', ''):
        return
    resource.setrlimit(resource.RLIMIT_AS, (MEMORY_LIMIT, MEMORY_LIMIT))


def env() -> dict:
    e = dict(os.environ)
    e['GAZEBO_MODEL_PATH'] = os.path.join(BAD, 'models')
    return e


def run_bounded(cmd: list, timeout: float = TIMEOUT) -> subprocess.CompletedProcess:
    """A program under the memory limit and a timeout (subprocess.TimeoutExpired when it hangs)."""
    return subprocess.run(cmd, capture_output=True, text=True, errors='replace', timeout=timeout,
                          preexec_fn=_limit_memory, env=env(), cwd=ROOT)


def run_check(path: str, kind: str) -> subprocess.CompletedProcess:
    """check_model for URDF and xacro, world_tool check for worlds."""
    if kind == 'world':
        return run_bounded([sys.executable, os.path.join(ROOT, 'scripts', 'world_tool'), 'check', path])
    return run_bounded([sys.executable, os.path.join(ROOT, 'scripts', 'check_model'), path])


API_RUNNER = r'''
import json, sys
from car import _core, xacro_tool
kind, path = sys.argv[1], sys.argv[2]
out = {'result': 'ok', 'message': ''}
try:
    if kind == 'world':
        w = _core.World(path)
        w.step(100)
    else:
        if kind == 'xacro':
            data = xacro_tool.expand(path)
        else:
            data = open(path, 'rb').read()
        _core.load_urdf_string(data, path)
        w = _core.World()
        w.spawn_urdf(data, 'robot', x=0, y=0, yaw=0)
        w.step(1000)
except xacro_tool.ExpandError as e:
    out = {'result': 'ExpandError', 'message': str(e)}
except _core.LoadError as e:
    out = {'result': 'LoadError', 'message': str(e)}
except _core.SimulationError as e:
    out = {'result': 'SimulationError', 'message': str(e)}
except ValueError as e:
    out = {'result': 'ValueError', 'message': str(e)}
print('RESULT ' + json.dumps(out))
'''


def run_api(path: str, kind: str) -> tuple:
    """The Python API (car._core) in a bounded subprocess: a world loads and steps 100 times, a robot (xacro
    expanded first) loads, spawns into the empty world and steps 1000 times. Returns (CompletedProcess,
    {'result': 'ok' | exception class, 'message': str} or None when it printed none)."""
    p = run_bounded([sys.executable, '-c', API_RUNNER, kind, path])
    for line in p.stdout.splitlines():
        if line.startswith('RESULT '):
            return p, json.loads(line[7:])
    return p, None


def messages(entry: dict, entry_point: str) -> list:
    """The substrings an entry point's output must hold: its own key (check_message, api_message,
    spawn_message) or the shared 'message'."""
    m = entry.get(entry_point + '_message', entry.get('message', []))
    return [m] if isinstance(m, str) else list(m)
