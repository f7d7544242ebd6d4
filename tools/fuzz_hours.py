#!/usr/bin/env python3
"""The fuzzing hours each loader has had on today's code, summed from car/test/fuzz/runs.tsv (RUNS.md).

A row counts for a target when its commit's loader sources are the same as HEAD's (`git diff --quiet COMMIT HEAD
-- PATHS`), so a change to a loader starts its count again and a change elsewhere does not. A row whose commit is
marked -dirty, or that git does not know, never counts; a row that executed nothing has 0 CPU s. Each target's loader
sources are LOADERS below (RUNS.md repeats them).

Usage: tools/fuzz_hours.py [--runs FILE] [--repo DIR] [--goal CPU_S] [--check]
  --check  exit 1 when a target has less than the goal (default 7 200 CPU s: 2 CPU-hours)
"""
import argparse
import csv
import os
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.realpath(__file__)))

# target -> the sources that parse, validate and resolve its input (paths from the repository's root). The plug-in
# kinds read their parameters in their own files (src/plugins/KIND/), beside their stepping, so every target whose
# input carries plug-ins counts the whole of src/plugins.
LOADERS = {
    'urdf': ['car/src/model', 'car/src/plugins'],
    'sdf_world': ['car/src/model', 'car/src/description', 'car/src/plugins'],
    'sdf_model': ['car/src/model', 'car/src/description', 'car/src/plugins'],
    'spawn': ['car/src/model', 'car/src/description', 'car/src/plugins'],
    'flatten': ['car/src/model', 'car/src/description'],
    'ros_control': ['car/src/plugins/ros_control'],
}


def git(repo, *args):
    return subprocess.run(['git', '-C', repo] + list(args), capture_output=True, text=True)


def same_loader(repo, commit, paths):
    """None when the row counts, else why not."""
    if commit.endswith('-dirty'):
        return 'built from a work tree that differed from its commit'
    if git(repo, 'cat-file', '-e', commit + '^{commit}').returncode != 0:
        return 'commit %s unknown to git' % commit
    diff = git(repo, 'diff', '--quiet', commit, 'HEAD', '--', *paths)
    if diff.returncode == 1:
        return 'the loader changed since %s' % commit
    if diff.returncode != 0:
        return 'git diff failed: %s' % diff.stderr.strip()
    return None


def tally(repo, rows):
    """{target: (cpu_s counted, rows counted, [(row, why not)])} for every target in LOADERS."""
    out = {t: [0, 0, []] for t in LOADERS}
    for row in rows:
        t = row['target']
        if t not in LOADERS:
            continue
        why = same_loader(repo, row['commit'], LOADERS[t])
        if why is None:
            out[t][0] += int(row['cpu_s'])
            out[t][1] += 1
        else:
            out[t][2].append((row, why))
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('--runs', default=os.path.join(ROOT, 'car', 'test', 'fuzz', 'runs.tsv'))
    ap.add_argument('--repo', default=ROOT)
    ap.add_argument('--goal', type=int, default=7200, help='CPU s per target (default 2 CPU-hours)')
    ap.add_argument('--check', action='store_true', help='exit 1 when a target is below the goal')
    a = ap.parse_args()
    with open(a.runs) as f:
        rows = list(csv.DictReader(f, delimiter='\t'))
    head = git(a.repo, 'rev-parse', '--short=12', 'HEAD').stdout.strip()
    print('fuzzing on the loaders as at %s (%s), goal %d CPU s per target' % (head, os.path.relpath(a.runs), a.goal))
    print('| target | loader sources | rows counted | CPU s | of the goal |')
    print('|---|---|---|---|---|')
    short = []
    counts = tally(a.repo, rows)
    for t, (cpu, n, _) in counts.items():
        print('| %s | %s | %d | %d | %.1f %% |' % (t, ', '.join(LOADERS[t]), n, cpu, 100.0 * cpu / a.goal))
        if cpu < a.goal:
            short.append(t)
    for t, (_, _, skipped) in counts.items():
        for row, why in skipped:
            print('not counted: %s %s %s CPU s: %s' % (t, row['start_utc'], row['cpu_s'], why))
    if short:
        print('below the goal: %s' % ', '.join(short))
    return 1 if a.check and short else 0


if __name__ == '__main__':
    sys.exit(main())
