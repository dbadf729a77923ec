#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Which hardware checkpoints PPSSPP fails, and which of those ge2gl passes (docs/conformance.md).

    PPSSPP_HEADLESS=/path/to/PPSSPPHeadless PSPAUTOTESTS=/path/to/pspautotests \
        python3 scripts/conformance_vs_ppsspp.py [BUILD_DIR]

Runs PPSSPP's headless build (software renderer) on the original test program (.prx) of every
test in the conformance suite (docs/conformance.md), compares what it prints with the test's
.expected file and its screenshot with .expected.bmp, counting checkpoints the way the suite does:
each KEY=value of a printed line (the precision tests' positions are decimal; a line without
KEY=value is one checkpoint) and each screenshot row over the first 480 columns. Then runs
BUILD_DIR/tests/test_conformance and matches ge2gl's failing checkpoints (label and hardware
value) against PPSSPP's. Prints per test and in total: checkpoints PPSSPP fails, how many of those
each ge2gl backend passes, and how many ge2gl fails that PPSSPP passes. PPSSPP and pspautotests are
not dependencies: without them the script says so and exits 0. Nothing of pspautotests is copied.
"""
import os
import re
import struct
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
KV = re.compile(r'([A-Za-z]+)=\s*([0-9a-fA-F]+)')
DECIMAL_KEYS = ('left', 'top')  # filtering/precision*: pixel positions printed in decimal


def suite_tests():
    """The suite's tests, from the table in docs/conformance.md."""
    with open(os.path.join(ROOT, 'docs', 'conformance.md')) as f:
        return [m.group(1) for m in (re.match(r'\| (gpu/[a-z0-9/]+) \|', l) for l in f) if m]


def fields(line):
    """(label, [(key, value text)]) of one printed line."""
    body = re.sub(r'^\s*(\[[a-z]\])?\s*', '', line)
    label, _, rest = body.partition(':')
    out = []
    for part in re.split(r',\s*', rest):
        found = KV.findall(part)
        if found:
            out.extend(found)
        elif re.fullmatch(r'[0-9a-fA-F]{6,8}', part.strip()) and out:
            out.append((out[-1][0] + '_c', part.strip()))  # an unnamed colour after a position
    return label.strip(), out


def value(key, text):
    return int(text, 10 if key in DECIMAL_KEYS else 16)


def printed_failures(actual, expected):
    """PPSSPP's failing checkpoints of a printing test: (section, label, key, hardware value)."""
    bad, section = [], ''
    for i in range(max(len(actual), len(expected))):
        a = actual[i] if i < len(actual) else ''
        e = expected[i] if i < len(expected) else ''
        if e.startswith('[x]'):
            section = e[3:].strip().rstrip(':')
        if a == e:
            continue
        label, ef = fields(e)
        got = dict(fields(a)[1])
        if not ef:
            tail = e.partition(':')[2].split()
            bad.append((section, label, 'line', int(tail[-1], 16) if tail and re.fullmatch(r'[0-9a-fA-F]+', tail[-1]) else None))
        for k, v in ef:
            if got.get(k, '').lower() != v.lower():
                bad.append((section, label, k, value(k, v)))
    return bad


def bmp_rows(path):
    with open(path, 'rb') as f:
        b = f.read()
    off = struct.unpack_from('<I', b, 10)[0]
    w, h = struct.unpack_from('<ii', b, 18)
    bpp = struct.unpack_from('<H', b, 28)[0] // 8
    stride = (w * bpp + 3) & ~3
    rows = []
    for y in range(abs(h)):
        sy = abs(h) - 1 - y if h > 0 else y
        r = b[off + sy * stride:off + sy * stride + w * bpp]
        rows.append([r[i * bpp:i * bpp + 3] for i in range(w)])
    return rows


def ge2gl_failures(build, backend):
    """{test: ([label, hardware, mask, used], failing rows)} from test_conformance's output."""
    exe = os.path.join(build, 'tests', 'test_conformance')
    out = subprocess.run([exe, '--gtest_filter=*/' + backend], capture_output=True, text=True).stdout
    fails, cur = {}, None
    for l in out.splitlines():
        m = re.match(r'(\S+) \[\w+\]: \d+/\d+ checkpoints', l)
        if m:
            cur = 'gpu/' + m.group(1)
            fails[cur] = ([], set())
            continue
        m = re.match(r'\s+FAIL row (\d+) ', l)
        if m and cur:
            fails[cur][1].add(int(m.group(1)))
            continue
        m = re.match(r'\s+FAIL (.*): got [0-9a-f]+, hardware ([0-9a-f]+) \(mask ([0-9a-f]+)\)', l)
        if m and cur:
            fails[cur][0].append([m.group(1), int(m.group(2), 16), int(m.group(3), 16), False])
    return fails


def words(s):
    return set(w for w in re.split(r'[\s:,=()]+', s.lower()) if w)


def matched(bad, ours):
    """How many of PPSSPP's failing printed checkpoints ge2gl also fails (same label words and
    hardware value), and how many of ge2gl's failures are left over."""
    for f in ours:
        f[3] = False
    both = 0
    for section, label, key, hw in bad:
        context = words(section + ' ' + label + ' ' + key.replace('_c', ' colour'))
        for f in ours:
            if f[3] or (hw is not None and (f[1] & f[2]) != (hw & f[2])):
                continue
            if words(f[0]) <= context | {'colour', 'color'}:
                f[3] = True
                both += 1
                break
    return both, sum(1 for f in ours if not f[3])


def main():
    ppsspp, tests_root = os.environ.get('PPSSPP_HEADLESS'), os.environ.get('PSPAUTOTESTS')
    if not ppsspp or not os.access(ppsspp, os.X_OK) or not tests_root:
        print('conformance_vs_ppsspp: set PPSSPP_HEADLESS and PSPAUTOTESTS (docs/benchmarks.md); nothing measured')
        return 0
    build = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, 'build')
    ours = {b: ge2gl_failures(build, b) for b in ('soft', 'gl')}
    totals = {'ppsspp': 0, 'soft': 0, 'gl': 0, 'soft_only': 0, 'gl_only': 0}
    print('%-34s %8s %12s %12s %14s' % ('test', 'PPSSPP', 'soft passes', 'gl passes', 'ge2gl only'))
    with tempfile.TemporaryDirectory() as tmp:
        for t in suite_tests():
            prx = os.path.join(tests_root, 'tests', t + '.prx')
            shot = os.path.join(tmp, 'shot.bmp')
            if os.path.exists(shot):
                os.remove(shot)
            run = subprocess.run([ppsspp, '--graphics=software', '--root', tests_root, '--timeout=10',
                                  '--screenshot-save=' + shot, prx], capture_output=True, text=True, cwd=tmp,
                                 errors='replace')
            actual = [l.rstrip('\r') for l in run.stdout.splitlines() if not l.startswith('Screenshot saved')]
            with open(os.path.join(tests_root, 'tests', t + '.expected'), errors='replace') as f:
                expected = [l.rstrip('\r\n') for l in f]
            ref = os.path.join(tests_root, 'tests', t + '.expected.bmp')
            screenshot = not [l for l in expected if l.strip()] and os.path.exists(ref)
            row = {}
            if screenshot:
                a, e = bmp_rows(shot), bmp_rows(ref)
                bad_rows = set(y for y in range(min(len(a), len(e), 272)) if a[y][:480] != e[y][:480])
                n = len(bad_rows)
                for b in ('soft', 'gl'):
                    rows = ours[b].get(t, ([], set()))[1]
                    row[b] = (len(bad_rows - rows), len(rows - bad_rows))
            else:
                bad = printed_failures(actual, expected)
                n = len(bad)
                for b in ('soft', 'gl'):
                    both, left = matched(bad, ours[b].get(t, ([], set()))[0])
                    row[b] = (n - both, left)
            totals['ppsspp'] += n
            for b in ('soft', 'gl'):
                totals[b] += row[b][0]
                totals[b + '_only'] += row[b][1]
            if n or row['soft'][1] or row['gl'][1]:
                print('%-34s %8d %12d %12d %7d / %d' % (t, n, row['soft'][0], row['gl'][0], row['soft'][1], row['gl'][1]))
    print('total: PPSSPP fails %d checkpoints; ge2gl passes %d of them (soft), %d (gl); ge2gl fails %d (soft) '
          'and %d (gl) that PPSSPP passes' % (totals['ppsspp'], totals['soft'], totals['gl'], totals['soft_only'],
                                               totals['gl_only']))
    return 0


if __name__ == '__main__':
    sys.exit(main())
