#!/usr/bin/python3
"""Measures kiln's speed against its accuracy and writes one CSV per experiment.

Usage: /usr/bin/python3 bench/speed_accuracy.py EXPERIMENT [--out DIR] [--quick]

Experiments (each writes DIR/<experiment>.csv, default DIR build/bench-results):
  suite         `kiln bench` on the benchmark suite: scenes/, generated meshes of 10k, 100k, 1M and 4M
                triangles, one mesh instanced 1000x, 10k analytic spheres, and ToyCar and
                2CylinderEngine from ../shared/assets when present. Per-case JSON and CSV beside it.
  antialiasing  spp 1..256 with stratified and random samples, and adaptive supersampling at several
                thresholds: RMSE of RGB against a 1024-spp stratified reference, and render time.
  tessellation  a sphere, a capped cylinder and a torus as exact quadrics and as meshes of 10^2..10^6
                triangles: silhouette, normal and depth error against the quadric, time and memory.
  accelerators  Embree, uniform grid, adaptive grid and brute force on 10^3..10^7 triangles and on
                instanced scenes (kiln_accel_benchmark --sweep): time per ray, build time, memory.
  threads       thread scaling of the tile scheduler (1 .. all cores) and tile size against time.
  all           every experiment above, in that order.

Everything runs the project's own binaries from build/ (built first with cmake), one measurement per
setting, all in one run, so ratios between settings are fair. Speed is reported, never asserted.
Needs numpy and OpenImageIO's Python module from Debian (python3-numpy, python3-openimageio), which is
why it runs on /usr/bin/python3.
"""

import argparse
import csv
import json
import os
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BUILD = os.path.join(ROOT, "build")
KILN = os.path.join(BUILD, "renderer", "app", "kiln")
MAKE_SCENES = os.path.join(BUILD, "bench", "make_bench_scenes")
ACCEL_BENCH = os.path.join(BUILD, "bench", "kiln_accel_benchmark")
ASSETS = os.path.join(os.path.dirname(ROOT), "shared", "assets")


def run(command, **kwargs):
    print("+ " + " ".join(command), file=sys.stderr, flush=True)
    return subprocess.run(command, check=True, **kwargs)


def build(targets):
    run(["cmake", "--build", BUILD, "--target"] + targets)


def write_csv(path, rows):
    if not rows:
        return
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        writer.writeheader()
        writer.writerows(rows)
    print("wrote " + path, file=sys.stderr)


def read_exr(path):
    """The EXR's channels as a dict name -> 2D float array, and its header attributes."""
    import numpy as np
    import OpenImageIO as oiio
    buf = oiio.ImageBuf(path)
    pixels = np.asarray(buf.get_pixels(oiio.FLOAT))
    spec = buf.spec()
    channels = {name: pixels[:, :, i] for i, name in enumerate(spec.channelnames)}
    attributes = {a.name: a.value for a in spec.extra_attribs}
    return channels, attributes


def render(asset, out, args):
    """Renders with kiln; returns (seconds of rendering from the EXR header, channels)."""
    run([KILN, "render", asset, "-o", out, "-q"] + args)
    channels, attributes = read_exr(out)
    return float(attributes["kiln/render_seconds"]), channels


def bench(asset, label, folder, args):
    """`kiln bench` one case; returns its JSON report."""
    json_path = os.path.join(folder, label + ".json")
    run([KILN, "bench", asset, "--json", json_path, "--csv", os.path.join(folder, label + ".csv"), "--label",
         label, "-q"] + args)
    with open(json_path) as f:
        return json.load(f)


# --- suite -----------------------------------------------------------------------------------------

def suite_cases(scenes, quick):
    cases = [("cornell_box", os.path.join(ROOT, "scenes", "cornell_box.gltf"), []),
             ("quadric_showcase", os.path.join(ROOT, "scenes", "quadric_showcase.gltf"), []),
             ("glass_showcase", os.path.join(ROOT, "scenes", "glass_showcase.gltf"),
              ["--environment", os.path.join(ROOT, "scenes", "glass_showcase_sky.hdr")])]
    for name in ["mesh_10k", "mesh_100k", "mesh_1m"] + ([] if quick else ["mesh_4m"]) + \
            ["instanced_1000x10k", "quadric_spheres_10k"]:
        cases.append((name, os.path.join(scenes, name + ".glb"), []))
    for name, path in [("ToyCar", "ToyCar/glTF/ToyCar.gltf"),
                       ("2CylinderEngine", "2CylinderEngine/glTF-Binary/2CylinderEngine.glb")]:
        if os.path.exists(os.path.join(ASSETS, path)):
            cases.append((name, os.path.join(ASSETS, path), []))
    return cases


def experiment_suite(out, quick):
    build(["kiln", "make_bench_scenes"])
    scenes = os.path.join(BUILD, "bench-scenes")
    run([MAKE_SCENES, scenes] + (["--skip-4m"] if quick else []))
    folder = os.path.join(out, "suite")
    os.makedirs(folder, exist_ok=True)
    rows = []
    for label, asset, extra in suite_cases(scenes, quick):
        r = bench(asset, label, folder, ["--width", "640", "--height", "480", "--repeat", "1" if quick else "3"] +
                  extra)
        kinds = {k["kind"] + "/" + k["query"]: k for k in r["kinds"]}
        cam, shadow = kinds.get("camera/intersect"), kinds.get("shadow/occluded")
        rows.append({
            "label": label, "triangles_unique": r["triangles"]["unique"], "triangles_placed": r["triangles"]["placed"],
            "instances": r["instances"], "threads": r["threads"], "load_s": r["load_seconds"],
            "build_s": r["build_seconds"], "first_pixel_s": r["first_pixel_seconds"], "render_s": r["render_seconds"],
            "peak_rss_mb": r["peak_rss_bytes"]["after_render"] / 1e6,
            "scene_memory_mb": r["scene_memory_bytes"] / 1e6, "queries": r["rays"]["queries"],
            "render_mrays_per_s": r["render_mrays_per_s"], "bare_mrays_per_s": r["bare_embree_mrays_per_s"],
            "render_over_bare": r["render_over_bare"],
            "camera_kiln_over_bare": cam["kiln_query_over_bare"] if cam else "",
            "shadow_kiln_over_bare": shadow["kiln_query_over_bare"] if shadow else "",
            "kiln_version": r["kiln_version"], "embree_version": r["embree_version"], "cpu": r["machine"]["cpu"]})
    write_csv(os.path.join(out, "suite.csv"), rows)


# --- antialiasing ----------------------------------------------------------------------------------

def rmse(a, b):
    import numpy as np
    d = np.stack([a[c] - b[c] for c in ("R", "G", "B")])
    return float(np.sqrt(np.mean(d * d)))


def experiment_antialiasing(out, quick):
    build(["kiln"])
    folder = os.path.join(out, "antialiasing")
    os.makedirs(folder, exist_ok=True)
    scene = os.path.join(ROOT, "scenes", "cornell_box.gltf")
    size = ["--width", "96" if quick else "160", "--height", "72" if quick else "120"]
    _, reference = render(scene, os.path.join(folder, "reference.exr"), size + ["--spp", "256" if quick else "1024"])
    rows = []
    spps = [1, 4, 16, 64] if quick else [1, 4, 16, 64, 256]
    for sampler in ("stratified", "random"):
        for spp in spps:
            seconds, image = render(scene, os.path.join(folder, "%s_%d.exr" % (sampler, spp)),
                                    size + ["--spp", str(spp), "--sampler", sampler])
            rows.append({"method": sampler, "setting": spp, "seconds": seconds, "rmse": rmse(image, reference)})
    for threshold in ([0.2, 0.05, 0.01] if quick else [0.2, 0.1, 0.05, 0.02, 0.01]):
        for depth in (2, 4):
            seconds, image = render(scene, os.path.join(folder, "adaptive_%g_%d.exr" % (threshold, depth)),
                                    size + ["--adaptive-threshold", str(threshold), "--adaptive-depth", str(depth)])
            rows.append({"method": "adaptive depth %d" % depth, "setting": threshold, "seconds": seconds,
                         "rmse": rmse(image, reference)})
    write_csv(os.path.join(out, "antialiasing.csv"), rows)


# --- tessellation ----------------------------------------------------------------------------------

def shape_errors(mesh, exact):
    """Silhouette error (pixels whose coverage differs, as a share of the exact silhouette), mean normal
    angle in degrees and mean relative depth error over pixels both cover."""
    import numpy as np
    a_mesh, a_exact = mesh["A"] > 0.5, exact["A"] > 0.5
    silhouette = float(np.sum(a_mesh != a_exact)) / max(1, int(np.sum(a_exact)))
    both = a_mesh & a_exact
    n_mesh = np.stack([mesh["N.X"], mesh["N.Y"], mesh["N.Z"]], axis=-1)[both]
    n_exact = np.stack([exact["N.X"], exact["N.Y"], exact["N.Z"]], axis=-1)[both]
    cos = np.clip(np.sum(n_mesh * n_exact, axis=-1), -1.0, 1.0)
    normal = float(np.degrees(np.mean(np.arccos(cos)))) if cos.size else 0.0
    depth = float(np.mean(np.abs(mesh["Z"][both] - exact["Z"][both]) / exact["Z"][both])) if cos.size else 0.0
    return silhouette, normal, depth


def experiment_tessellation(out, quick):
    build(["kiln", "make_bench_scenes"])
    scenes = os.path.join(BUILD, "bench-scenes", "tessellation")
    run([MAKE_SCENES, scenes, "--tessellation"])
    folder = os.path.join(out, "tessellation")
    os.makedirs(folder, exist_ok=True)
    size = ["--width", "256", "--height", "192"]
    # Float AOVs for the images: half-float normals quantise at about 1e-3, degrees of error.
    exact_image = size + ["--float"]
    rows = []
    counts = [100, 1000, 10000, 100000] if quick else [100, 1000, 10000, 100000, 1000000]
    for shape in ("sphere", "cylinder", "torus"):
        exact_asset = os.path.join(scenes, shape + "_quadric.glb")
        _, exact = render(exact_asset, os.path.join(folder, shape + "_quadric.exr"), exact_image)
        timing = bench(exact_asset, shape + "_quadric", folder, size + ["--repeat", "3"])
        rows.append({"shape": shape, "representation": "quadric", "triangles": 0,
                     "render_s": timing["render_seconds"], "build_s": timing["build_seconds"],
                     "peak_rss_mb": timing["peak_rss_bytes"]["after_render"] / 1e6,
                     "scene_memory_mb": timing["scene_memory_bytes"] / 1e6,
                     "silhouette_error": 0.0, "normal_error_deg": 0.0, "depth_error": 0.0})
        for n in counts:
            asset = os.path.join(scenes, "%s_mesh_%d.glb" % (shape, n))
            _, image = render(asset, os.path.join(folder, "%s_mesh_%d.exr" % (shape, n)), exact_image)
            timing = bench(asset, "%s_mesh_%d" % (shape, n), folder, size + ["--repeat", "3"])
            silhouette, normal, depth = shape_errors(image, exact)
            rows.append({"shape": shape, "representation": "mesh", "triangles": timing["triangles"]["unique"],
                         "render_s": timing["render_seconds"], "build_s": timing["build_seconds"],
                         "peak_rss_mb": timing["peak_rss_bytes"]["after_render"] / 1e6,
                         "scene_memory_mb": timing["scene_memory_bytes"] / 1e6,
                         "silhouette_error": silhouette, "normal_error_deg": normal, "depth_error": depth})
    write_csv(os.path.join(out, "tessellation.csv"), rows)


# --- accelerators ----------------------------------------------------------------------------------

def experiment_accelerators(out, quick):
    build(["kiln_accel_benchmark"])
    os.makedirs(out, exist_ok=True)
    run([ACCEL_BENCH, "20000" if quick else "200000", "--sweep", "--csv", os.path.join(out, "accelerators.csv")])


# --- threads ---------------------------------------------------------------------------------------

def experiment_threads(out, quick):
    build(["kiln", "make_bench_scenes"])
    scenes = os.path.join(BUILD, "bench-scenes")
    asset = os.path.join(scenes, "mesh_100k.glb")
    if not os.path.exists(asset):
        run([MAKE_SCENES, scenes, "--skip-4m"])
    folder = os.path.join(out, "threads")
    os.makedirs(folder, exist_ok=True)
    size = ["--width", "320" if quick else "640", "--height", "240" if quick else "480"]
    rows = []
    cores = os.cpu_count() or 1
    thread_counts = sorted({1, 2, 4, 8, 16, cores} & set(range(1, cores + 1)))
    for threads in thread_counts:
        r = bench(asset, "threads_%d" % threads, folder, size + ["--threads", str(threads), "--repeat", "3"])
        rows.append({"sweep": "threads", "threads": threads, "tile_size": 32, "render_s": r["render_seconds"]})
    for tile in (4, 8, 16, 32, 64, 128):
        r = bench(asset, "tile_%d" % tile, folder, size + ["--tile-size", str(tile), "--repeat", "3"])
        rows.append({"sweep": "tile size", "threads": r["threads"], "tile_size": tile, "render_s": r["render_seconds"]})
    write_csv(os.path.join(out, "threads.csv"), rows)


EXPERIMENTS = {"suite": experiment_suite, "antialiasing": experiment_antialiasing,
               "tessellation": experiment_tessellation, "accelerators": experiment_accelerators,
               "threads": experiment_threads}


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("experiment", choices=list(EXPERIMENTS) + ["all"])
    parser.add_argument("--out", default=os.path.join(BUILD, "bench-results"))
    parser.add_argument("--quick", action="store_true", help="smaller sizes and fewer settings (a smoke run)")
    args = parser.parse_args()
    started = time.time()
    for name in (list(EXPERIMENTS) if args.experiment == "all" else [args.experiment]):
        EXPERIMENTS[name](args.out, args.quick)
    print("done in %.0f s; results in %s" % (time.time() - started, args.out), file=sys.stderr)


if __name__ == "__main__":
    main()
