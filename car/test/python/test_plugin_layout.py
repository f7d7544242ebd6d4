"""A kind is one folder and one line (docs/ARCHITECTURE.md "Where code lives"): no file in a kind's folder under
src/plugins/ includes a file of another kind's folder. Code more than one kind uses lives in src/plugins/common/,
which is no kind; the table of kinds (src/plugins/registry.cpp) is the one file that names them all."""
import os
import re

PLUGINS = os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.realpath(__file__)))),
                       'src', 'plugins')
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)


def kind_folders():
    return sorted(d for d in os.listdir(PLUGINS)
                  if os.path.isdir(os.path.join(PLUGINS, d)) and d != 'common')


def foreign_includes(folder):
    """(file, include) for each include of a file in folder that reaches another kind's folder."""
    kinds = set(kind_folders())
    out = []
    for name in sorted(os.listdir(os.path.join(PLUGINS, folder))):
        if not name.endswith(('.cpp', '.hpp')):
            continue
        with open(os.path.join(PLUGINS, folder, name), encoding='utf-8') as f:
            for inc in INCLUDE.findall(f.read()):
                parts = os.path.normpath(os.path.join(folder, inc)).split(os.sep)
                # "../x/y.hpp" from folder -> x/y.hpp; "x/y.hpp" as written (the include path holds src/plugins)
                target = parts[0] if parts[0] in kinds else (inc.split('/')[0] if '/' in inc else folder)
                if target in kinds and target != folder:
                    out.append((name, inc))
    return out


def test_there_are_kind_folders():
    # the check below must have something to read: the 28 kind folders of today, give or take a few
    assert len(kind_folders()) >= 25, kind_folders()


def test_no_kind_includes_another_kinds_folder():
    offending = {k: foreign_includes(k) for k in kind_folders()}
    offending = {k: v for k, v in offending.items() if v}
    assert offending == {}, 'kinds that include another kind: %r (move the shared code to src/plugins/common/)' % offending


def test_the_check_sees_a_foreign_include(tmp_path, monkeypatch):
    # the check itself: a kind including another kind's header is found
    for k in ('alpha', 'beta'):
        (tmp_path / k).mkdir()
    (tmp_path / 'alpha' / 'alpha.cpp').write_text('#include "../beta/beta.hpp"\n#include "alpha.hpp"\n')
    (tmp_path / 'beta' / 'beta.cpp').write_text('#include "../common/shared.hpp"\n')
    (tmp_path / 'common').mkdir()
    monkeypatch.setattr(__import__(__name__), 'PLUGINS', str(tmp_path))
    assert foreign_includes('alpha') == [('alpha.cpp', '../beta/beta.hpp')]
    assert foreign_includes('beta') == []
