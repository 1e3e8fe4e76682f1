"""Table rows from render_ab.sh output: medians over rounds and the median of per-round ratios to BASE.
Usage: render_ab_ratios.py AB_OUTPUT.txt BASE_LABEL"""
import statistics as st
import sys
from collections import defaultdict

rows = [l.split() for l in open(sys.argv[1]) if l.strip() and not l.startswith("#")]
base = sys.argv[2]
by = defaultdict(dict)
for row in rows:
    by[row[0]][row[1]] = [float(x) for x in row[2:]]
labels = list(dict.fromkeys(row[1] for row in rows))
print("| variant | CPU s | wall s | CPU : base (range) | wall : base |")
print("|---|---|---|---|---|")
for l in labels:
    cpu = [by[r][l][0] for r in by]
    wall = [by[r][l][1] for r in by]
    rc = [by[r][l][0] / by[r][base][0] for r in by]
    rw = [by[r][l][1] / by[r][base][1] for r in by]
    print(f"| {l} | {st.median(cpu):.2f} | {st.median(wall):.2f} | "
          f"{st.median(rc):.3f} ({min(rc):.3f}-{max(rc):.3f}) | {st.median(rw):.3f} |")
