"""The adversarial corpus through check_model / world_tool check and the Python API: for each case of
test/data/bad/EXPECTED.yaml the exit code (or exception) and message substrings, under a 2 GB address-space limit
and a 60 s timeout, with no crash (a signal, a traceback) and nothing read from /etc/passwd."""
import os

import pytest

import bad_corpus

CASES = bad_corpus.cases()


@pytest.fixture(scope='module')
def gen_dir(tmp_path_factory):
    return str(tmp_path_factory.mktemp('bad_generated'))


def _no_crash(p):
    assert p.returncode >= 0, 'killed by signal %d\n%s' % (-p.returncode, p.stderr[-2000:])
    assert 'Traceback' not in p.stderr, p.stderr[-3000:]
    assert bad_corpus.PASSWD_MARK not in p.stdout + p.stderr


def test_the_corpus_has_at_least_50_cases():
    assert len(CASES) >= 50


@pytest.mark.parametrize('name,entry', CASES, ids=[c[0] for c in CASES])
def test_check_tool(name, entry, gen_dir):
    p = bad_corpus.run_check(bad_corpus.path_of(name, entry, gen_dir), entry['kind'])
    _no_crash(p)
    out = p.stdout + p.stderr
    assert p.returncode == entry['exit'], out[-3000:]
    for m in bad_corpus.messages(entry, 'check'):
        assert m in out, out[-3000:]


@pytest.mark.parametrize('name,entry', CASES, ids=[c[0] for c in CASES])
def test_python_api(name, entry, gen_dir):
    p, r = bad_corpus.run_api(bad_corpus.path_of(name, entry, gen_dir), entry['kind'])
    _no_crash(p)
    assert r is not None, p.stderr[-3000:]
    expected = entry.get('api', 'ok' if entry['exit'] == 0 else 'LoadError')
    assert r['result'] == expected, r
    if expected != 'ok':
        for m in bad_corpus.messages(entry, 'api'):
            assert m in r['message'], r


def test_external_entity_files_exist_to_be_read():
    # the external-entity cases point at /etc/passwd; the test above proves its content never shows
    assert os.path.exists('/etc/passwd')
