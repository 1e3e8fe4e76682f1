"""Build time, Embree memory and render CPU time of each BVH build option, from `kiln bench` JSON
(one folder per scene holding <option>_<round>.json, as bench/perf/build_options_ab.sh writes them
under docs/performance/build-options/json/). The chart the default (medium, not compact) was chosen
from (docs/performance.md, "BVH build options").

usage: /usr/bin/python3 bench/charts/bvh_options_chart.py OUT_DIR SCENE_DIR...
"""
import json
import statistics
import sys
from pathlib import Path

from chart_io import plt, save

OPTIONS = ["low", "medium", "high", "compact"]


def medians(folder):
    """Per option: median build seconds, Embree MB after the build, render CPU seconds."""
    out = {}
    for option in OPTIONS:
        runs = [json.loads(p.read_text()) for p in sorted(folder.glob(f"{option}_*.json"))]
        if not runs:
            continue
        out[option] = (
            statistics.median(r["build_seconds"] for r in runs),
            statistics.median(r["embree_bytes"]["after_build"] for r in runs) / 1e6,
            statistics.median(r["render_cpu_seconds"] for r in runs),
        )
    return out


def main():
    out = Path(sys.argv[1])
    scenes = [Path(p) for p in sys.argv[2:]]
    fig, axes = plt.subplots(1, 3, figsize=(12, 3.8))
    titles = ["BVH build (s)", "Embree memory after build (MB)", "render CPU time (relative to medium)"]
    width = 0.8 / len(OPTIONS)
    for s, folder in enumerate(scenes):
        m = medians(folder)
        base = m["medium"]
        for o, option in enumerate(OPTIONS):
            if option not in m:
                continue
            values = [m[option][0], m[option][1], m[option][2] / base[2]]
            for a, v in enumerate(values):
                axes[a].bar(s + (o - 1.5) * width, v, width, color=f"C{o}", label=option if s == 0 else None)
    for a, title in enumerate(titles):
        axes[a].set_title(title)
        axes[a].set_xticks(range(len(scenes)))
        axes[a].set_xticklabels([f.name.removeprefix("bvh_") for f in scenes])
    axes[0].set_yscale("log")
    axes[2].set_ylim(0.8, 1.25)
    axes[2].axhline(1.0, color="grey", lw=0.8)
    axes[0].legend()
    save(fig, out, "bvh_options")


if __name__ == "__main__":
    main()
