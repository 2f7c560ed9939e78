#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Sums the big blocks of a Scripts/heap-trace.c trace by their first callers (addr2line).

Usage: heap-trace-report.py TRACE [block|alloc] [frames=4]
  block: the blocks live at the peak of the live heap (what makes the peak);
  alloc: every big block the run asked for (the fresh memory it touched).
"""
import collections
import re
import subprocess
import sys

FRAME = re.compile(r'(\S+)\+(0x[0-9a-f]+)')
# Allocator and container frames say nothing about the owner.
SKIP = ('operator new', 'std::', '__gnu_cxx', 'vtkAOSDataArrayTemplate', 'vtkGenericDataArray',
        'vtkDataArray', 'vtkBuffer', 'vtkAbstractArray', 'vtkSOADataArray', 'Add', 'malloc')


def main():
    lines = open(sys.argv[1]).read().splitlines()
    kind = sys.argv[2] if len(sys.argv) > 2 else 'block'
    depth = int(sys.argv[3]) if len(sys.argv) > 3 else 4
    frames = collections.defaultdict(set)
    for line in lines:
        if line.startswith(kind + ' '):
            for m in FRAME.finditer(line):
                frames[m.group(1)].add(m.group(2))
    names = {}
    for lib, offsets in frames.items():
        offsets = sorted(offsets)
        # addresses are return addresses: the call is one byte before
        out = subprocess.run(['addr2line', '-f', '-C', '-e', lib] +
                             [hex(int(o, 16) - 1) for o in offsets],
                             capture_output=True, text=True).stdout.splitlines()
        for i, o in enumerate(offsets):
            name = out[2 * i] if 2 * i < len(out) else '?'
            names[(lib, o)] = re.sub(r'\(.*', '', name)[:70]
    total = collections.Counter()
    count = collections.Counter()
    for line in lines:
        if not line.startswith(kind + ' '):
            if line.startswith('peak'):
                print(line)
            continue
        mib = float(line.split()[1])
        # VTK's core library has no symbols for its array templates: leave it out.
        callers = [names.get((m.group(1), m.group(2)), '?') for m in FRAME.finditer(line)
                   if 'CommonCore' not in m.group(1) and 'heap-trace' not in m.group(1)]
        callers = [c for c in callers if not c.startswith(SKIP)]
        key = ' < '.join(callers[:depth])
        total[key] += mib
        count[key] += 1
    for key, mib in total.most_common():
        print('%8.1f MiB %3d x  %s' % (mib, count[key], key))
    print('total %.1f MiB in blocks >= 4 MiB' % sum(total.values()))


if __name__ == '__main__':
    main()
