"""README.md is a user's manual: every relative Markdown link in it and in docs/*.md (and CHANGELOG.md) names a
file that exists, none of them points at a file outside the repository, the README stays at most 300 lines, and
it carries no dates or issue numbers (those belong in CHANGELOG.md and docs/BENCH.md)."""
import glob
import os
import re

# realpath: under catkin this file is reached through .ws/src/car/test -> the repository's test/
# the repository: README.md, CHANGELOG.md and docs/ sit beside car/
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(os.path.realpath(__file__)))))
README = os.path.join(ROOT, 'README.md')

# [text](target) and ![alt](target); target up to whitespace or ')' (an optional "title" may follow)
LINK = re.compile(r'!?\[[^\]]*\]\(\s*<?([^)\s>]+)>?(?:\s+"[^"]*")?\s*\)')
FENCE = re.compile(r'^(```|~~~).*?^\1', re.S | re.M)
CODE_SPAN = re.compile(r'`[^`\n]*`')
INDENTED_CODE = re.compile(r'^(?: {4}|\t).*$', re.M)


def _documents():
    return [README, os.path.join(ROOT, 'CHANGELOG.md')] + sorted(glob.glob(os.path.join(ROOT, 'docs', '*.md')))


def relative_links(text):
    """The relative link targets of a Markdown text, code blocks and code spans left out, anchors dropped."""
    text = FENCE.sub('', text)
    text = INDENTED_CODE.sub('', text)
    text = CODE_SPAN.sub('', text)
    out = []
    for target in LINK.findall(text):
        if re.match(r'^[a-z][a-z0-9+.-]*:', target, re.I) or target.startswith('#'):
            continue  # http:, https:, mailto:, or an anchor in the same page
        out.append(target.split('#', 1)[0])
    return out


def broken_links(path):
    with open(path, encoding='utf-8') as f:
        text = f.read()
    base = os.path.dirname(path)
    return [t for t in relative_links(text) if not os.path.exists(os.path.join(base, t))]


def test_link_parser_finds_links_and_images_but_not_code_or_urls():
    text = ('see [a](docs/A.md) and ![pic](docs/p.png "title") and [b](B.md#part)\n'
            '`[not](code.md)` [web](https://x.org) [top](#top)\n'
            '```\n[fenced](f.md)\n```\n'
            '    [indented](i.md)\n')
    assert relative_links(text) == ['docs/A.md', 'docs/p.png', 'B.md']


def test_every_relative_link_in_the_readme_and_docs_resolves():
    checked = 0
    broken = {}
    for path in _documents():
        assert os.path.exists(path), 'missing document %s' % path
        bad = broken_links(path)
        if bad:
            broken[os.path.relpath(path, ROOT)] = bad
        with open(path, encoding='utf-8') as f:
            checked += len(relative_links(f.read()))
    assert checked > 20, 'only %d relative links found: is the parser reading the files?' % checked
    assert not broken, 'links to files that do not exist: %s' % broken


def test_no_document_points_outside_the_repository():
    # a user's clone has only the repository: no /work/ checkout, no shared spec beside it
    outside = re.compile(r'/work/|shared/spec|shared spec')
    found = {}
    for path in _documents():
        with open(path, encoding='utf-8') as f:
            lines = ['%d: %s' % (i, line.strip()) for i, line in enumerate(f, 1) if outside.search(line)]
        if lines:
            found[os.path.relpath(path, ROOT)] = lines
    assert not found, 'documents that point outside the repository: %s' % found


def test_readme_is_at_most_300_lines():
    with open(README, encoding='utf-8') as f:
        n = len(f.read().splitlines())
    assert n <= 300, 'README.md has %d lines; move detail into docs/' % n


def test_readme_has_no_dates():
    with open(README, encoding='utf-8') as f:
        dated = [line for line in f if '2026-' in line]
    assert not dated, 'dates belong in CHANGELOG.md or docs/BENCH.md: %s' % dated


def test_readme_has_no_issue_numbers():
    with open(README, encoding='utf-8') as f:
        cited = [line for line in f if re.search(r'\bissues? \d+|(?<![\w&])#\d+\b', line, re.I)]
    assert not cited, 'issue numbers belong in CHANGELOG.md or commit messages: %s' % cited
