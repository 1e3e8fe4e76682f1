"""Medians of threads.sh output (usage: threads_summary.py runs.csv): render seconds and the 1 -> 2 thread speed-up per round."""
import csv
import statistics
import sys
from collections import defaultdict

rows = list(csv.DictReader(open(sys.argv[1])))
groups = defaultdict(list)
for r in rows:
    groups[(r["scene"], r["binary"])].append(r)
print("| scene | binary | 2 threads s | 1 thread beside another s | 1 thread alone s "
      "| speed-up vs beside (range) | speed-up vs alone (range) |")
print("|---|---|---|---|---|---|---|")
for (scene, binary), rs in sorted(groups.items(), key=lambda kv: (kv[0][0], kv[0][1] != "before")):
    two = [float(r["two_threads"]) for r in rs]
    beside = [float(r["one_thread_beside_another"]) for r in rs]
    alone = [float(r["one_thread_alone"]) for r in rs]
    s_beside = [b / t for b, t in zip(beside, two)]
    s_alone = [a / t for a, t in zip(alone, two)]
    med = statistics.median
    print(f"| {scene} | {binary} | {med(two):.3f} | {med(beside):.3f} | {med(alone):.3f} "
          f"| {med(s_beside):.2f} ({min(s_beside):.2f}-{max(s_beside):.2f}) "
          f"| {med(s_alone):.2f} ({min(s_alone):.2f}-{max(s_alone):.2f}) |")
