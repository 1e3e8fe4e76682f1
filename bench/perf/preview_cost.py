"""What --preview adds to a render: alternated runs of `kiln render ASSET -o a.exr` without a preview,
with --preview a.png and with --preview a.jpg, for one or more builds, measuring each process's user
CPU, system CPU and wall time (os.wait4, so nothing but kiln is counted). Prints per build and variant
the medians over rounds and the median of the per-round differences to the same build's run without
a preview, in milliseconds: the preview's own cost with the load's drift taken out.
Usage: preview_cost.py ROUNDS NAME=KILN [NAME=KILN ...] -- ASSET [render options]"""
import os
import statistics as st
import subprocess
import sys
import tempfile
import time

rounds = int(sys.argv[1])
split = sys.argv.index("--")
builds = [b.split("=", 1) for b in sys.argv[2:split]]
render_args = sys.argv[split + 1:]
variants = ["none", "png", "jpg"]
folder = tempfile.mkdtemp(prefix="preview_cost_")


def run(kiln, variant):
    command = [kiln, "render", *render_args, "-o", f"{folder}/a.exr", "-q"]
    if variant != "none":
        command += ["--preview", f"{folder}/a.{variant}"]
    start = time.perf_counter()
    child = subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    _, status, usage = os.wait4(child.pid, 0)
    wall = time.perf_counter() - start
    error = child.stderr.read().decode()
    child.stderr.close()
    if status != 0:
        raise SystemExit(f"{' '.join(command)} failed: {error}")
    return usage.ru_utime, usage.ru_stime, wall


runs = {(name, v): [] for name, _ in builds for v in variants}
for _ in range(rounds):
    for name, kiln in builds:
        for v in variants:
            runs[(name, v)].append(run(kiln, v))

print(f"{rounds} rounds alternated: kiln render {' '.join(render_args)} -o a.exr -q [--preview a.png|a.jpg]")
print("| build | preview | user ms | sys ms | wall ms | added user ms | added wall ms |")
print("|---|---|---|---|---|---|---|")
for name, _ in builds:
    base = runs[(name, "none")]
    for v in variants:
        own = runs[(name, v)]
        user = st.median(r[0] for r in own) * 1e3
        system = st.median(r[1] for r in own) * 1e3
        wall = st.median(r[2] for r in own) * 1e3
        added = [(o[0] - b[0]) * 1e3 for o, b in zip(own, base)]
        added_wall = [(o[2] - b[2]) * 1e3 for o, b in zip(own, base)]
        extra = "" if v == "none" else f"{st.median(added):+.0f} | {st.median(added_wall):+.0f}"
        print(f"| {name} | {v} | {user:.0f} | {system:.0f} | {wall:.0f} | {extra or '- | -'} |")
