#!/usr/bin/python3
"""Builds one static HTML page with the six speed-against-accuracy charts, the benchmark suite
table, rendered images beside them, and the commands that reproduced each.

Usage: /usr/bin/python3 bench/report.py [RESULTS_DIR]   (default build/bench-results)

Run the measurements first:
  /usr/bin/python3 bench/speed_accuracy.py all          # charts 1, 2, 3, 6 and the suite
  bench/stability_charts.sh                             # charts 4 and 5
  /usr/bin/python3 bench/charts/speed_accuracy_charts.py build/bench-results
The page is RESULTS_DIR/report.html; images are converted to PNG next to it (tools/exr_to_png.py).
"""
import csv
import html
import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

CHARTS = [
    ("chart1_antialiasing", "1. Anti-aliasing: RMSE against a 1024-spp reference vs time",
     "/usr/bin/python3 bench/speed_accuracy.py antialiasing", ["antialiasing/stratified_1", "antialiasing/reference"]),
    ("chart2_tessellation", "2. Exact quadrics vs tessellated meshes: silhouette, normal and depth error vs time "
     "and memory", "/usr/bin/python3 bench/speed_accuracy.py tessellation",
     ["tessellation/torus_quadric", "tessellation/torus_mesh_1000"]),
    ("chart3_accelerators", "3. Accelerators: time per ray vs scene size, build time and memory",
     "/usr/bin/python3 bench/speed_accuracy.py accelerators", []),
    ("stability/chart4_self_intersection", "4. Self-intersection: acne and leak rate vs scale and translation",
     "bench/stability_charts.sh", []),
    ("stability/chart5_solvers", "5. Quadric solvers: error and miss rate vs distance against ns/ray",
     "bench/stability_charts.sh", []),
    ("chart6_threads", "6. Tile scheduler: thread scaling and tile size",
     "/usr/bin/python3 bench/speed_accuracy.py threads", []),
]


def png_of(results, stem):
    """A PNG preview of RESULTS/stem.exr (made once), or None."""
    exr, png = results / f"{stem}.exr", results / f"{stem}.png"
    if not exr.exists():
        return None
    if not png.exists() or png.stat().st_mtime < exr.stat().st_mtime:
        subprocess.run([sys.executable, str(ROOT / "tools" / "exr_to_png.py"), str(exr), str(png)], check=True)
    return png


def suite_table(results):
    path = results / "suite.csv"
    if not path.exists():
        return "<p>No suite results (run <code>bench/speed_accuracy.py suite</code>).</p>"
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    columns = ["label", "triangles_unique", "triangles_placed", "instances", "threads", "load_s", "build_s",
               "render_s", "peak_rss_mb", "scene_memory_mb", "render_mrays_per_s", "bare_mrays_per_s", "render_over_bare",
               "camera_kiln_over_bare", "shadow_kiln_over_bare"]

    def cell(value):
        try:
            number = float(value)
            return f"{number:.4g}"
        except ValueError:
            return html.escape(value)

    head = "".join(f"<th>{html.escape(c)}</th>" for c in columns)
    body = "".join("<tr>" + "".join(f"<td>{cell(r.get(c, ''))}</td>" for c in columns) + "</tr>" for r in rows)
    machine = html.escape(rows[0].get("cpu", "")) if rows else ""
    return (f"<p>Machine: {machine}. <code>render_over_bare</code>: kiln's whole render (shading included) "
            f"against the bare Embree loop over the same rays; <code>*_kiln_over_bare</code>: kiln's "
            f"accelerator queries against the bare loop, per ray kind.</p><table><tr>{head}</tr>{body}</table>")


def main():
    results = Path(sys.argv[1] if len(sys.argv) > 1 else ROOT / "build" / "bench-results").resolve()
    parts = ["<!doctype html><meta charset='utf-8'><title>kiln: speed against accuracy</title>",
             "<style>body{font-family:sans-serif;max-width:1300px;margin:auto}img{max-width:100%}"
             "table{border-collapse:collapse;font-size:12px}td,th{border:1px solid #ccc;padding:2px 5px}"
             ".images img{height:180px;margin-right:8px}code{background:#f3f3f3}</style>",
             "<h1>kiln: speed against accuracy</h1>",
             f"<p>Results in <code>{html.escape(str(results))}</code>.</p>",
             "<h2>Benchmark suite</h2>", "<p><code>/usr/bin/python3 bench/speed_accuracy.py suite</code></p>",
             suite_table(results)]
    for stem, title, command, images in CHARTS:
        parts.append(f"<h2>{html.escape(title)}</h2><p><code>{html.escape(command)}</code></p>")
        chart = results / f"{stem}.png"
        if chart.exists():
            parts.append(f"<img src='{os.path.relpath(chart, results)}'>")
        else:
            parts.append("<p>(not measured yet)</p>")
        previews = [png_of(results, s) for s in images]
        previews = [p for p in previews if p]
        if previews:
            parts.append("<div class='images'>" + "".join(
                f"<img src='{os.path.relpath(p, results)}' title='{html.escape(p.stem)}'>" for p in previews) +
                "</div>")
    out = results / "report.html"
    out.write_text("\n".join(parts) + "\n")
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
