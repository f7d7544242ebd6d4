"""tools/fuzz_hours.py: a fuzzing run counts for a target only while that target's loader sources are as they were
at the run's commit; -dirty and unknown commits never count. A throw-away git repository with three commits: A, B
(changes car/src/model, a loader source of every target but ros_control), C (changes docs only)."""
import os
import subprocess
import sys

import pytest

from conftest import REPO

TOOL = os.path.join(REPO, 'tools', 'fuzz_hours.py')
HEADER = 'start_utc\ttarget\tcommit\tnice\twall_s\tcpu_s\tinputs\tcov\tft\tcorpus_files\tfindings\tnote\n'


def git(repo, *args):
    return subprocess.run(['git', '-C', str(repo)] + list(args), check=True, capture_output=True,
                          text=True).stdout.strip()


def commit(repo, path, text, message):
    f = repo / path
    f.parent.mkdir(parents=True, exist_ok=True)
    f.write_text(text)
    git(repo, 'add', path)
    git(repo, '-c', 'user.name=t', '-c', 'user.email=t@t', 'commit', '-q', '-m', message)
    return git(repo, 'rev-parse', '--short=12', 'HEAD')


@pytest.fixture
def repo(tmp_path):
    r = tmp_path / 'repo'
    r.mkdir()
    git(r, 'init', '-q')
    ids = {'A': commit(r, 'car/src/model/urdf_loader.cpp', 'a\n', 'A'),
           'B': commit(r, 'car/src/model/urdf_loader.cpp', 'b\n', 'B'),
           'C': commit(r, 'docs/RELIABILITY.md', 'c\n', 'C')}
    return r, ids


def run(repo, rows, *args):
    runs = repo / 'runs.tsv'
    runs.write_text(HEADER + ''.join('2026-11-29T00:00:0%dZ\t%s\t%s\t10\t100\t%d\t1\t1\t1\t1\t0\t-\n' % (k, t, c, s)
                                     for k, (t, c, s) in enumerate(rows)))
    return subprocess.run([sys.executable, TOOL, '--runs', str(runs), '--repo', str(repo)] + list(args),
                          capture_output=True, text=True)


def line(out, target):
    return next(l for l in out.splitlines() if l.startswith('| %s |' % target))


def test_a_run_before_its_loader_changed_does_not_count(repo):
    r, ids = repo
    out = run(r, [('urdf', ids['A'], 900), ('urdf', ids['B'], 1000), ('urdf', ids['C'], 200)]).stdout
    assert line(out, 'urdf') == '| urdf | car/src/model, car/src/plugins | 2 | 1200 | 16.7 % |'
    assert 'not counted: urdf 2026-11-29T00:00:00Z 900 CPU s: the loader changed since %s' % ids['A'] in out


def test_a_change_to_another_targets_loader_keeps_the_count(repo):
    r, ids = repo
    out = run(r, [('ros_control', ids['A'], 7200)]).stdout
    assert line(out, 'ros_control') == '| ros_control | car/src/plugins/ros_control | 1 | 7200 | 100.0 % |'


def test_dirty_and_unknown_commits_never_count(repo):
    r, ids = repo
    out = run(r, [('spawn', ids['C'] + '-dirty', 500), ('spawn', '0123456789ab', 600)]).stdout
    assert line(out, 'spawn') == '| spawn | car/src/model, car/src/description, car/src/plugins | 0 | 0 | 0.0 % |'
    assert ('not counted: spawn 2026-11-29T00:00:00Z 500 CPU s: built from a work tree that differed from its '
            'commit') in out
    assert 'not counted: spawn 2026-11-29T00:00:01Z 600 CPU s: commit 0123456789ab unknown to git' in out


def test_check_fails_naming_the_targets_below_the_goal(repo):
    r, ids = repo
    rows = [(t, ids['C'], 7200) for t in ('urdf', 'sdf_world', 'sdf_model', 'spawn', 'ros_control')]
    res = run(r, rows + [('flatten', ids['C'], 7199)], '--check')
    assert res.returncode == 1
    assert res.stdout.splitlines()[-1] == 'below the goal: flatten'


def test_check_passes_when_every_target_has_its_hours(repo):
    r, ids = repo
    rows = [(t, ids['C'], 3600) for t in ('urdf', 'sdf_world', 'sdf_model', 'spawn', 'ros_control', 'flatten')]
    res = run(r, rows + rows, '--check')
    assert res.returncode == 0, res.stdout
    assert 'below the goal' not in res.stdout
