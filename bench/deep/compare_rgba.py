#!/usr/bin/env python3
"""cmp.py A.exr B.exr [LAYER.exr ...]: max/mean |A-B| over RGBA; with layers, split into edge pixels
(some layer's alpha strictly between 0 and 1) and interior (the rest)."""
import re, subprocess, sys, os, tempfile

def load(path):
    tmp = tempfile.mktemp(suffix='.exr')
    subprocess.run(['oiiotool', path, '--ch', 'R,G,B,A', '-o', tmp], check=True)
    out = subprocess.run(['oiiotool', '--dumpdata', tmp], capture_output=True, text=True, check=True).stdout
    os.unlink(tmp)
    return [[float(v) for v in l.split(':', 1)[1].split()] for l in out.splitlines()[1:] if 'Pixel' in l]

a, b = load(sys.argv[1]), load(sys.argv[2])
d = [max(abs(x - y) for x, y in zip(p, q)) for p, q in zip(a, b)]
r = [max(abs(x - y) / max(1.0, abs(y)) for x, y in zip(p, q)) for p, q in zip(a, b)]
print(f"max relative (to max(1,|v|)): {max(r):.3g}")
def report(name, idx):
    if not idx: return
    v = [d[i] for i in idx]
    print(f'{name}: {len(v)} px, max {max(v):.3g}, mean {sum(v)/len(v):.3g}, px > 1e-3: {sum(x > 1e-3 for x in v)}')
report('all', list(range(len(d))))
if len(sys.argv) > 3:
    edge = [False] * len(d)
    for p in sys.argv[3:]:
        for i, px in enumerate(load(p)):
            edge[i] |= 0 < px[3] < 1
    report('interior', [i for i in range(len(d)) if not edge[i]])
    report('edges', [i for i in range(len(d)) if edge[i]])
