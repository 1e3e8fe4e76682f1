#!/usr/bin/python3
"""Charts 1, 2, 3 and 6 of the speed-against-accuracy study, from bench/speed_accuracy.py's CSV files.

chart1_antialiasing: RMSE against a 1024-spp reference vs render time, one line per sampling method.
chart2_tessellation: silhouette, normal and depth error of meshes against the exact quadric, vs
  render time and vs memory; the quadric itself is drawn as a star at zero error.
chart3_accelerators: ns per ray vs scene size per backend, with build time and memory.
chart6_threads: speed-up over one thread vs threads, and render time vs tile size.
Each as PNG and SVG next to the CSV files; a chart whose CSV is missing is skipped.

usage: speed_accuracy_charts.py RESULTS_DIR
"""
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from chart_io import read, save  # noqa: E402




def chart1(rows, out):
    fig, ax = plt.subplots(figsize=(7, 5))
    for method in sorted({r["method"] for r in rows}):
        pts = sorted((float(r["seconds"]), float(r["rmse"]), r["setting"]) for r in rows if r["method"] == method)
        ax.plot([p[0] for p in pts], [p[1] for p in pts], marker="o", label=method)
        for seconds, error, setting in pts:
            ax.annotate(setting, (seconds, error), textcoords="offset points", xytext=(4, 3), fontsize=7)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("render time (s)")
    ax.set_ylabel("RMSE of RGB against the 1024-spp reference")
    ax.set_title("anti-aliasing: error against time (labels: spp or threshold)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    save(fig, out, "chart1_antialiasing")


def chart2(rows, out):
    errors = (("silhouette_error", "silhouette error (share of the exact silhouette)"),
              ("normal_error_deg", "mean normal error (degrees)"), ("depth_error", "mean relative depth error"))
    fig, axes = plt.subplots(2, 3, figsize=(15, 8.5))
    for col, (key, label) in enumerate(errors):
        for row, (cost, cost_label) in enumerate((("render_s", "render time (s)"),
                                                 ("scene_memory_mb", "memory the scene added (MB, resident set)"))):
            ax = axes[row][col]
            for shape, colour in zip(("sphere", "cylinder", "torus"), ("C0", "C1", "C2")):
                meshes = sorted((float(r[cost]), max(float(r[key]), 1e-6), int(r["triangles"])) for r in rows
                                if r["shape"] == shape and r["representation"] == "mesh")
                ax.plot([m[0] for m in meshes], [m[1] for m in meshes], marker="o", color=colour,
                        label=f"{shape} mesh")
                for c, e, n in meshes:
                    ax.annotate(f"{n:g}", (c, e), textcoords="offset points", xytext=(3, 3), fontsize=6)
                exact = [r for r in rows if r["shape"] == shape and r["representation"] == "quadric"]
                if exact:
                    ax.plot([float(exact[0][cost])], [1e-6], marker="*", ms=14, color=colour, ls="none",
                            label=f"{shape} quadric (exact)")
            ax.set_xscale("log")
            ax.set_yscale("log")
            ax.set_xlabel(cost_label)
            ax.set_ylabel(label + " (exact drawn at 1e-6)")
            ax.grid(True, which="both", alpha=0.3)
    axes[0][0].legend(fontsize=7)
    fig.suptitle("exact quadric against tessellated meshes (labels: triangles)")
    save(fig, out, "chart2_tessellation")


def chart3(rows, out):
    fig, axes = plt.subplots(1, 3, figsize=(16, 5))
    spheres = [r for r in rows if r["scene"].startswith("sphere_")]
    for backend in ("embree", "grid", "adaptive-grid", "brute-force"):
        pts = sorted((int(r["triangles"]), float(r["ns_per_ray"]), float(r["build_seconds"]), float(r["memory_mb"]))
                     for r in spheres if r["backend"] == backend)
        if not pts:
            continue
        for ax, index in zip(axes, (1, 2, 3)):
            ax.plot([p[0] for p in pts], [max(p[index], 1e-6) for p in pts], marker="o", label=backend)
    instanced = [r for r in rows if r["scene"].startswith("instanced_")]
    for r in instanced:
        axes[0].plot([int(r["triangles"])], [float(r["ns_per_ray"])], marker="s", ls="none", color="grey")
        axes[0].annotate(f"{r['backend']} {r['scene']}", (int(r["triangles"]), float(r["ns_per_ray"])),
                         textcoords="offset points", xytext=(3, 3), fontsize=6)
    for ax, label in zip(axes, ("ns per ray (one thread)", "build time (s)", "memory (MB, RSS growth)")):
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("triangles (placed)")
        ax.set_ylabel(label)
        ax.grid(True, which="both", alpha=0.3)
    axes[0].legend()
    fig.suptitle("accelerators against scene size (grey squares: instanced scenes)")
    save(fig, out, "chart3_accelerators")


def chart6(rows, out):
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.5))
    threads = sorted((int(r["threads"]), float(r["render_s"])) for r in rows if r["sweep"] == "threads")
    if threads:
        base = threads[0][1]
        axes[0].plot([t for t, _ in threads], [base / s for _, s in threads], marker="o", label="measured")
        axes[0].plot([t for t, _ in threads], [t for t, _ in threads], ls="--", color="grey", label="ideal")
        axes[0].set_xlabel("threads")
        axes[0].set_ylabel("speed-up over one thread")
        axes[0].legend()
        axes[0].grid(True, alpha=0.3)
    tiles = sorted((int(r["tile_size"]), float(r["render_s"])) for r in rows if r["sweep"] == "tile size")
    if tiles:
        best = min(s for _, s in tiles)
        axes[1].plot([t for t, _ in tiles], [s / best for _, s in tiles], marker="o")
        axes[1].axhline(1.1, ls="--", color="grey", label="10% off the best")
        axes[1].set_xscale("log", base=2)
        axes[1].set_xlabel("tile size (pixels)")
        axes[1].set_ylabel("render time / best")
        axes[1].legend()
        axes[1].grid(True, alpha=0.3)
    fig.suptitle("tile scheduler: thread scaling and tile size")
    save(fig, out, "chart6_threads")


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    out = Path(sys.argv[1])
    for name, chart in (("antialiasing", chart1), ("tessellation", chart2), ("accelerators", chart3),
                        ("threads", chart6)):
        path = out / f"{name}.csv"
        if path.exists():
            chart(read(path), out)
        else:
            print(f"skipped {name}: no {path}")


if __name__ == "__main__":
    main()
