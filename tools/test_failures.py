#!/usr/bin/env python3
"""Prints each failed or errored test case in catkin's JUnit results, with the head of its message, so the
last lines of a CI log say which test failed and why. Usage: test_failures.py <test_results dir>"""
import os
import sys
import xml.etree.ElementTree as ET

LINES = 15


def main(root):
    for dirpath, _, files in sorted(os.walk(root)):
        for name in sorted(files):
            if not name.endswith('.xml'):
                continue
            path = os.path.join(dirpath, name)
            try:
                tree = ET.parse(path)
            except ET.ParseError as e:
                print('%s: unreadable result file (%s)' % (path, e))
                continue
            for case in tree.iter('testcase'):
                for kind in ('failure', 'error'):
                    for bad in case.findall(kind):
                        message = [l for l in (bad.get('message') or '').splitlines() if l.strip()]
                        trace = [l for l in (bad.text or '').splitlines() if l.strip()]
                        # unittest's own frames say nothing: start after the last of them
                        own = [i for i, l in enumerate(trace) if 'unittest/case.py' in l]
                        if own:
                            trace = trace[:1] + trace[own[-1] + 2:]
                        trace = [l for l in trace if set(l.strip()) != {'^'}]
                        print('---- %s %s: %s.%s' % (kind.upper(), name, case.get('classname', ''),
                                                     case.get('name', '')))
                        for l in message[:5] + trace[-LINES:]:
                            print('  ' + l)


if __name__ == '__main__':
    main(sys.argv[1] if len(sys.argv) > 1 else '.')
