#!/usr/bin/python3
"""Charts 4 and 5 of the stability study from the CSV files of bench/stability_study.

chart4_self_intersection: shadow-acne rate and thin-gap leak rate against scene scale and
translation, one line per offset method (solid: triangle, dashed: sphere).
chart5_solvers: sphere and torus solver failure rate and surface error against distance, and
error against ns/ray. Each as PNG and SVG, next to the CSV files.

usage: stability_charts.py RESULTS_DIR
"""
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from chart_io import read, save  # noqa: E402
import numpy as np  # noqa: E402

FLOOR = 1e-5  # zero rates are drawn here (below 1/rays), on log axes




def chart4(rows, out):
    methods = sorted({r["method"] for r in rows if r["method"] != "error_bound"},
                     key=lambda m: float(m.split("=")[1])) + ["error_bound"]
    colors = dict(zip(methods, plt.cm.viridis(np.linspace(0, 0.9, len(methods) - 1))))
    colors["error_bound"] = "red"
    fig, axes = plt.subplots(2, 2, figsize=(12, 8.5))
    for col, sweep in enumerate(("scale", "translation")):
        for row_i, (rate, title) in enumerate((("acne_rate", "shadow acne"), ("leak_rate", "leak through a 4e-5 gap"))):
            ax = axes[row_i][col]
            for shape, style in (("plane", "-"), ("sphere", "--")):
                for m in methods:
                    pts = [r for r in rows if r["sweep"] == sweep and r["shape"] == shape and r["method"] == m]
                    x = np.array([float(r[sweep]) for r in pts])
                    if sweep == "translation":
                        x = np.maximum(x, 0.1)  # translation 0 drawn at 0.1
                    y = np.maximum([float(r[rate]) for r in pts], FLOOR)
                    ax.plot(x, y, style, marker="o", ms=3, color=colors[m],
                            lw=2.5 if m == "error_bound" else 1.2,
                            label=f"{m} ({'triangle' if shape == 'plane' else 'sphere'})")
            ax.set_xscale("log")
            ax.set_yscale("log")
            ax.set_ylim(FLOOR / 2, 1.5)
            ax.set_xlabel("scene scale" if sweep == "scale" else "translation (scale 1; 0 drawn at 0.1)")
            ax.set_ylabel(f"{title} rate (0 drawn at {FLOOR:g})")
            ax.set_title(f"{title} vs {sweep}")
            ax.grid(True, which="major", alpha=0.3)
    handles, labels = axes[0][0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=7, fontsize=7)
    fig.suptitle("Chart 4: self-intersection, fixed epsilons vs kiln's error-bound offset")
    fig.tight_layout(rect=(0, 0.08, 1, 0.97))
    for ext in ("png", "svg"):
        fig.savefig(out / f"chart4_self_intersection.{ext}", dpi=110)
    plt.close(fig)


def chart5(spheres, tori, out):
    fig, axes = plt.subplots(2, 3, figsize=(15, 8.5))
    groups = [("sphere", spheres, [("toward", "-")]), ("torus", tori, [("random", "-"), ("grazing", "--")])]
    for row_i, (shape, rows, kinds) in enumerate(groups):
        solvers = list(dict.fromkeys(r["solver"] for r in rows))
        colors = dict(zip(solvers, plt.cm.tab10(np.arange(len(solvers)))))
        ax_fail, ax_err, ax_cost = axes[row_i]
        for kind, style in kinds:
            for s in solvers:
                pts = [r for r in rows if r["solver"] == s and r["rays_kind"] == kind]
                d = np.array([float(r["distance"]) for r in pts])
                fail = np.maximum([float(r["failure_rate"]) for r in pts], FLOOR)
                err = np.maximum([float(r["max_error"]) for r in pts], 1e-17)
                ns = np.array([float(r["ns_per_ray"]) for r in pts])
                label = f"{s} ({kind})"
                lw = 2.5 if s == "kiln" else 1.2
                ax_fail.plot(d, fail, style, marker="o", ms=3, color=colors[s], lw=lw, label=label)
                ax_err.plot(d, err, style, marker="o", ms=3, color=colors[s], lw=lw, label=label)
                ax_cost.scatter(ns, err, color=colors[s], marker="o" if kind != "grazing" else "^", s=14, label=label)
        ax_fail.set(xscale="log", yscale="log", ylim=(FLOOR / 2, 1.5), xlabel="distance (radii)",
                    ylabel=f"failure rate: miss + invented + off by >1e-4 (0 at {FLOOR:g})",
                    title=f"{shape}: failure rate vs distance")
        ax_err.set(xscale="log", yscale="log", xlabel="distance (radii)", ylabel="max distance of hit from surface (radii)",
                   title=f"{shape}: hit error vs distance")
        ax_cost.set(xscale="log", yscale="log", xlabel="ns per ray (solve only)", ylabel="max hit error (radii)",
                    title=f"{shape}: error vs cost (one point per distance)")
        for ax in (ax_fail, ax_err, ax_cost):
            ax.grid(True, alpha=0.3)
        ax_err.legend(fontsize=7)
    fig.suptitle("Chart 5: ray solvers, error and failure rate vs distance, against ns/ray")
    save(fig, out, "chart5_solvers")


def main():
    if len(sys.argv) != 2:
        print(__doc__, file=sys.stderr)
        return 2
    out = Path(sys.argv[1])
    chart4(read(out / "self_intersection.csv"), out)
    chart5(read(out / "sphere_solvers.csv"), read(out / "torus_solvers.csv"), out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
