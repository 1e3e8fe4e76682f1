#!/usr/bin/python3
"""Time kiln against peer renderers on the same scenes: Blender Cycles (set up Whitted-like) and
POV-Ray 3.7. A measurement, never a test: nothing here asserts a speed.

Cases (640x480, 2 threads by default):
  toycar-16spp    ToyCar (../shared/assets) through a wrapper glTF that keeps the asset's first
                  camera (Camera001) and adds one point light: kiln and Cycles (POV-Ray reads no glTF)
                  (this case and the quadrics run kiln with --lighting file: the file's lights alone)
  quadrics-16spp  scenes/peer_quadrics.gltf and bench/peers/peer_quadrics.pov, written together by
                  tools/make_peer_quadric_scene.py: kiln and POV-Ray (Cycles has no analytic quadrics)
  quadrics-1spp   the same at 1 sample per pixel (POV-Ray without antialiasing)
  helmet-env-16spp  DamagedHelmet (../shared/assets) lit by kiln's studio environment alone
                  (share/environments/studio.exr): kiln `--lighting studio`, Cycles with the same EXR
                  as its World (bench/peers/blender_environment.py: diffuse bounces 0, the importer's
                  materials) through kiln's camera, read from a 1-spp kiln render's EXR before the
                  rounds (how far the two images agree: bench/peers/environment_compare.py)
  toycar-env-16spp  the same for ToyCar (its own file, its first camera, no added light)
  *-env-1pair-16spp the environment cases with kiln at --environment-samples 1: one direction drawn
                  from the map and one from the material's lobes at each shading point, the samples
                  a Cycles path takes there (one light sample, one BSDF sample); kiln's default is 2

Each round runs every case with kiln, then Cycles, then POV-Ray, so machine load drifts over all
renderers alike; medians over rounds are reported. A peer that is not installed is skipped with a
message. Times: the whole process (wall and CPU of the child), and each renderer's own render
phase: kiln's render time (EXR renderTimeSeconds, also on its summary line, with load and build),
Cycles' render_pre..render_post (sync + BVH build + sampling; bench/peers/blender_render.py), and
POV-Ray's Trace Time from its statistics. Ray counts: kiln's summary line (camera, shadow,
reflection, refraction) and POV-Ray's statistics (rays, shadow ray tests, reflected, refracted).

Writes into the results folder: runs.json (every run), summary.json, table.md, table.csv,
chart.png, images/ (the last round's renders as PNG and side-by-side comparisons).

Usage: /usr/bin/python3 bench/peers/peer_bench.py [--kiln build/renderer/app/kiln]
           [--out build/bench-results/peers] [--rounds 3] [--quick] [--cases a,b]
Needs python3-matplotlib and python3-numpy for the chart, oiiotool for the PNGs, and
python3-openimageio for the environment cases' camera.
"""

import argparse
import json
import math
import os
import platform
import re
import resource
import shutil
import statistics
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))
RENDERERS = ["kiln", "cycles", "povray"]

# The file's lights and nothing else, as the peers are set up: kiln's default (--lighting auto) adds its
# studio environment to a file's lights, where Cycles' world is black here and POV-Ray has none.
FILE_LIGHTS_ONLY = ["--lighting", "file"]

# The environment cases' assets under --assets, by the case name's first word.
ENVIRONMENT_ASSETS = {"helmet": ("DamagedHelmet", "glTF-Binary", "DamagedHelmet.glb"),
                      "toycar": ("ToyCar", "glTF", "ToyCar.gltf")}

# ToyCar's light: above and to the camera's right, so the car casts a shadow on its cloth.
TOYCAR_LIGHT = {"position": [0.03, 0.09, 0.06], "intensity": 0.06, "color": [1.0, 1.0, 1.0]}


def log(*parts):
    print("peer_bench:", *parts, flush=True)


def child_cpu():
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def run_timed(cmd, cwd=None, log_path=None):
    """Run cmd, return (wall s, child CPU s, combined output); raise with the tail on failure."""
    cpu0, t0 = child_cpu(), time.perf_counter()
    p = subprocess.run(cmd, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, errors="replace")
    wall, cpu = time.perf_counter() - t0, child_cpu() - cpu0
    if log_path:
        with open(log_path, "w", encoding="utf-8") as f:
            f.write(" ".join(cmd) + "\n" + p.stdout)
    if p.returncode != 0:
        raise RuntimeError("%s failed (exit %d): %s" % (cmd[0], p.returncode, p.stdout[-2000:]))
    return wall, cpu, p.stdout


# ---- scenes ------------------------------------------------------------------------------------

def toycar_wrapper(asset, folder, width, height):
    """A glTF beside the results that uses ToyCar's buffers and images in place, keeps its first
    camera (aspect set to the image's) and adds TOYCAR_LIGHT; kiln needs --allow-outside-files."""
    with open(asset, encoding="utf-8") as f:
        g = json.load(f)
    src = os.path.dirname(os.path.abspath(asset))
    for item in g.get("buffers", []) + g.get("images", []):
        if "uri" in item and not item["uri"].startswith("data:"):
            item["uri"] = os.path.relpath(os.path.join(src, item["uri"]), folder).replace(os.sep, "/")
    scene = g["scenes"][g.get("scene", 0)]
    camera_nodes = [i for i in scene["nodes"] if "camera" in g["nodes"][i]]
    first = camera_nodes[0]
    scene["nodes"] = [i for i in scene["nodes"] if i not in camera_nodes[1:]]
    g["cameras"][g["nodes"][first]["camera"]]["perspective"]["aspectRatio"] = width / height
    # Only the kept camera: renumber so that it is camera 0 (blender_render.py reads cameras[0]).
    cam = g["nodes"][first]["camera"]
    g["cameras"] = [g["cameras"][cam]]
    for i, n in enumerate(g["nodes"]):
        if "camera" in n:
            if i == first:
                n["camera"] = 0
            else:
                del n["camera"]
    g.setdefault("extensions", {})["KHR_lights_punctual"] = {"lights": [
        {"name": "peer key", "type": "point", "color": TOYCAR_LIGHT["color"], "intensity": TOYCAR_LIGHT["intensity"]}]}
    g["nodes"].append({"name": "peer key", "translation": TOYCAR_LIGHT["position"],
                       "extensions": {"KHR_lights_punctual": {"light": 0}}})
    scene["nodes"].append(len(g["nodes"]) - 1)
    used = g.setdefault("extensionsUsed", [])
    if "KHR_lights_punctual" not in used:
        used.append("KHR_lights_punctual")
    path = os.path.join(folder, "toycar_peer.gltf")
    with open(path, "w", encoding="utf-8") as f:
        json.dump(g, f)
    return path


def environment_case(args, key, asset, folder, width, height):
    """kiln's camera (the file's first, or kiln's framing), as blender_environment.py takes it: from the
    worldToCamera and worldToNDC of a 1-spp kiln render (numpy and OpenImageIO needed here only)."""
    import environment_compare
    exr = os.path.join(folder, "%s-env-camera.exr" % key)
    run_timed([args.kiln, "render", asset, "-o", exr, "--width", str(width), "--height", str(height), "--spp", "1",
               "--lighting", "studio"])
    camera = environment_compare.blender_camera(environment_compare.read_exr(exr)[2], width, height)
    path = os.path.join(folder, "%s-env-camera.json" % key)
    with open(path, "w", encoding="utf-8") as f:
        json.dump(camera, f)
    return path


def find_toycar(assets):
    path = os.path.join(assets, "ToyCar", "glTF", "ToyCar.gltf")
    return path if os.path.isfile(path) else None


# ---- renderers ---------------------------------------------------------------------------------

KILN_SUMMARY = re.compile(r"load ([\d.]+) s, build ([\d.]+) s, render ([\d.]+) s \((\d+) camera, (\d+) shadow, "
                          r"(\d+) reflection, (\d+) refraction rays")


def run_kiln(args, case, out_exr, log_path):
    cmd = [args.kiln, "render", case["gltf"], "-o", out_exr, "--width", str(case["width"]), "--height",
           str(case["height"]), "--spp", str(case["spp"]), "--threads", str(args.threads), "--max-depth", "8",
           "--progress-interval", "1000"]
    if case.get("outside"):
        cmd.append("--allow-outside-files")
    cmd += case.get("kiln_args", [])
    wall, cpu, text = run_timed(cmd, log_path=log_path)
    m = KILN_SUMMARY.search(text)
    if not m:
        raise RuntimeError("no kiln summary line in: " + text[-500:])
    load, build, render = (float(m.group(i)) for i in (1, 2, 3))
    rays = {k: int(m.group(i)) for k, i in (("camera", 4), ("shadow", 5), ("reflection", 6), ("refraction", 7))}
    return {"wall_s": wall, "cpu_s": cpu, "render_s": render, "load_s": load, "build_s": build, "rays": rays}


def run_cycles(args, case, out_exr, log_path):
    stats = out_exr[:-4] + ".stats.json"
    script = "blender_environment.py" if case.get("environment") else "blender_render.py"
    cmd = [args.blender, "-b", "--factory-startup", "-noaudio", "-t", str(args.threads), "--python",
           os.path.join(HERE, script), "--", case["gltf"], out_exr, stats,
           "--width", str(case["width"]), "--height", str(case["height"]), "--spp", str(case["spp"]),
           "--threads", str(args.threads)]
    if case.get("environment"):
        cmd += ["--environment", case["environment"], "--camera", case["camera_json"]]
    wall, cpu, text = run_timed(cmd, log_path=log_path)
    if not os.path.isfile(stats):
        raise RuntimeError("Blender wrote no statistics; see " + log_path)
    with open(stats, encoding="utf-8") as f:
        s = json.load(f)
    row = {"wall_s": wall, "cpu_s": cpu, "render_s": s["render_s"], "import_s": s["import_s"],
           "blender": s["blender"]}
    row.update(cycles_phases(text))
    return row


def cycles_phases(text):
    """Phases from the clock on Cycles' status lines ('Fra:1 ... | Time:00:04.75 | ... | Sample 16/16'):
    sync (objects, images, shaders) until BVH building starts, the BVH build until the step after
    it, sampling from 'Sample 0/N' to 'Finished'; cycles_s is Cycles' own total."""
    steps = []
    for line in text.splitlines():
        m = re.match(r"Fra:\d+ .*?\| Time:(\d+):(\d+\.\d+) \|.*\| ([^|]+?)(?: \| ([^|]*))?$", line.strip())
        if m:
            steps.append((int(m.group(1)) * 60 + float(m.group(2)), m.group(3).strip(), (m.group(4) or "").strip()))
    bvh = [i for i, s in enumerate(steps) if "BVH" in s[1] or "BVH" in s[2]]
    sample0 = next((s[0] for s in steps if re.match(r"Sample 0/", s[1])), None)
    finished = next((s[0] for s in steps if s[1] == "Finished"), None)
    out = {}
    if bvh and bvh[-1] + 1 < len(steps):
        out["sync_s"] = steps[bvh[0]][0]
        out["bvh_s"] = steps[bvh[-1] + 1][0] - steps[bvh[0]][0]
    if sample0 is not None and finished is not None:
        out["sampling_s"] = finished - sample0
        out["cycles_s"] = finished
    return out


POV_TIME = re.compile(r"(Parse|Bounding|Photon|Radiosity|Trace) Time:\s+\d+ hours\s+\d+ minutes\s+\d+ seconds "
                      r"\(([\d.]+) seconds\)")


def pov_count(text, label):
    m = re.search(label + r":\s+(\d+)", text)
    return int(m.group(1)) if m else None


def run_povray(args, case, out_exr, log_path):
    folder = os.path.dirname(out_exr)
    pov = os.path.join(folder, os.path.basename(case["pov"]))
    if os.path.abspath(pov) != os.path.abspath(case["pov"]):
        shutil.copyfile(case["pov"], pov)  # POV-Ray writes only below its working folder
    aa = ["+A0.0", "+AM1", "+R%d" % int(round(math.sqrt(case["spp"])))] if case["spp"] > 1 else ["-A"]
    cmd = [args.povray, "-D", "-P", "+V", "+WT%d" % args.threads, "+W%d" % case["width"], "+H%d" % case["height"],
           *aa, "+FE", "+O" + os.path.basename(out_exr), os.path.basename(pov)]
    wall, cpu, text = run_timed(cmd, cwd=folder, log_path=log_path)
    times = {k.lower() + "_s": float(v) for k, v in POV_TIME.findall(text)}
    spp = re.search(r"Smpls/Pxl:\s+([\d.]+)", text)
    rays = {"rays": pov_count(text, "Rays"), "shadow_tests": pov_count(text, "Shadow Ray Tests"),
            "reflected": pov_count(text, "Reflected Rays"), "refracted": pov_count(text, "Refracted Rays"),
            "samples_per_pixel": float(spp.group(1)) if spp else None}
    row = {"wall_s": wall, "cpu_s": cpu, "render_s": times.get("trace_s"), "rays": rays}
    row.update({k: v for k, v in times.items() if k != "trace_s"})
    return row


# ---- report ------------------------------------------------------------------------------------

def med(values):
    values = [v for v in values if v is not None]
    return statistics.median(values) if values else None


def summarise(runs):
    out = {}
    for r in runs:
        out.setdefault((r["case"], r["renderer"]), []).append(r)
    summary = []
    for (case, renderer), rows in out.items():
        s = {"case": case, "renderer": renderer, "rounds": len(rows)}
        for key in ("render_s", "wall_s", "cpu_s"):
            vals = [r[key] for r in rows if r.get(key) is not None]
            s[key] = med(vals)
            s[key + "_min"] = min(vals) if vals else None
            s[key + "_max"] = max(vals) if vals else None
        for key in ("load_s", "build_s", "import_s", "sync_s", "bvh_s", "sampling_s", "parse_s", "bounding_s"):
            if any(key in r for r in rows):
                s[key] = med([r.get(key) for r in rows])
        s["rays"] = rows[-1].get("rays")
        summary.append(s)
    kiln = {s["case"]: s for s in summary if s["renderer"] == "kiln"}
    for s in summary:
        k = kiln.get(s["case"])
        if k and s["renderer"] != "kiln":
            # Per-round ratios, median: each round's peer time over the same round's kiln time.
            for key in ("render_s", "wall_s", "cpu_s"):
                ratios = []
                for r in runs:
                    if r["case"] == s["case"] and r["renderer"] == s["renderer"]:
                        kr = next((x for x in runs if x["case"] == s["case"] and x["renderer"] == "kiln"
                                   and x["round"] == r["round"]), None)
                        if kr and kr.get(key) and r.get(key):
                            ratios.append(r[key] / kr[key])
                s["kiln_speedup_" + key[:-2]] = med(ratios)
    return summary


def fmt(v, digits=3):
    if v is None:
        return "–"
    return ("%." + str(digits) + "g") % v


def rays_text(s):
    r = s.get("rays") or {}
    if s["renderer"] == "kiln":
        return "%s cam, %s shadow, %s refl, %s refr" % tuple(fmt(r.get(k), 4) for k in
                                                            ("camera", "shadow", "reflection", "refraction"))
    if s["renderer"] == "povray":
        return "%s rays, %s shadow tests, %s refl, %s refr (%s smpl/px)" % (
            fmt(r.get("rays"), 4), fmt(r.get("shadow_tests"), 4), fmt(r.get("reflected"), 4),
            fmt(r.get("refracted"), 4), fmt(r.get("samples_per_pixel"), 3))
    return "–"


def phases_text(s):
    if s["renderer"] == "kiln":
        return "load %s, build %s" % (fmt(s.get("load_s")), fmt(s.get("build_s")))
    if s["renderer"] == "cycles":
        return "import %s, sync %s, BVH %s, sampling %s" % tuple(
            fmt(s.get(k)) for k in ("import_s", "sync_s", "bvh_s", "sampling_s"))
    return "parse %s, bounding %s" % (fmt(s.get("parse_s")), fmt(s.get("bounding_s")))


def write_tables(summary, folder, meta):
    head = ["case", "renderer", "render phase s", "process wall s", "process CPU s", "kiln speed-up (render)",
            "kiln speed-up (wall)", "kiln speed-up (CPU)", "phases s", "rays"]
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    csv = [",".join(head)]
    for s in summary:
        cells = [s["case"], s["renderer"],
                 "%s (%s–%s)" % (fmt(s["render_s"]), fmt(s["render_s_min"]), fmt(s["render_s_max"])),
                 "%s (%s–%s)" % (fmt(s["wall_s"]), fmt(s["wall_s_min"]), fmt(s["wall_s_max"])),
                 fmt(s["cpu_s"]),
                 ("%.2fx" % s["kiln_speedup_render"]) if s.get("kiln_speedup_render") else "–",
                 ("%.2fx" % s["kiln_speedup_wall"]) if s.get("kiln_speedup_wall") else "–",
                 ("%.2fx" % s["kiln_speedup_cpu"]) if s.get("kiln_speedup_cpu") else "–",
                 phases_text(s), rays_text(s)]
        lines.append("| " + " | ".join(cells) + " |")
        csv.append(",".join('"%s"' % c.replace('"', "'") for c in cells))
    text = "\n".join(lines) + "\n"
    notes = ["", "Medians of %d rounds (min–max in brackets); speed-up = peer time / kiln time, median of "
             "per-round ratios; process CPU = user + system time of the whole process, the measure least "
             "moved by other load on the machine. %s" % (meta["rounds"], meta["settings"]), "",
             "- load average (1 min) before each run: %s" % meta.get("load_range", "?")]
    notes += ["- " + k + ": " + str(v) for k, v in meta["machine"].items()]
    notes += ["- skipped: " + s for s in meta["skipped"]]
    with open(os.path.join(folder, "table.md"), "w", encoding="utf-8") as f:
        f.write(text + "\n".join(notes) + "\n")
    with open(os.path.join(folder, "table.csv"), "w", encoding="utf-8") as f:
        f.write("\n".join(csv) + "\n")
    return text


def write_chart(summary, folder):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        log("no matplotlib (apt-get install python3-matplotlib): chart skipped")
        return None
    cases = []
    for s in summary:
        if s["case"] not in cases:
            cases.append(s["case"])
    colours = {"kiln": "#c0392b", "cycles": "#2471a3", "povray": "#239b56"}
    # Wider with more cases; the case names are turned so that long ones do not overlap.
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(max(10, 1.6 * len(cases)), 4.6),
                                   gridspec_kw={"width_ratios": [3, 2]})
    width = 0.18
    labelled = set()
    for i, case in enumerate(cases):
        # Only the renderers that ran this case, centred on it: render phase dark, process wall light.
        bars = [(s, key) for r in RENDERERS for s in summary if s["case"] == case and s["renderer"] == r
                for key in ("render_s", "wall_s") if s.get(key)]
        for k, (s, key) in enumerate(bars):
            label = "%s %s" % (s["renderer"], "render" if key == "render_s" else "process wall")
            ax1.bar(i + (k - (len(bars) - 1) / 2) * width, s[key], width, color=colours[s["renderer"]],
                    alpha=1.0 if key == "render_s" else 0.45, label=None if label in labelled else label)
            labelled.add(label)
    ax1.set_yscale("log")
    ax1.set_xticks(range(len(cases)))
    ax1.set_xticklabels(cases, rotation=30, ha="right", fontsize=8)
    ax1.set_ylabel("seconds (median, log scale)")
    ax1.set_title("time per scene")
    ax1.legend(fontsize=7, ncol=2)
    labels, cols, ups = [], [], {"render": [], "wall": [], "cpu": []}
    for s in summary:
        if s.get("kiln_speedup_render") or s.get("kiln_speedup_wall"):
            labels.append("%s\nvs %s" % (s["case"], s["renderer"]))
            for key in ups:
                ups[key].append(s.get("kiln_speedup_" + key) or 0)
            cols.append(colours[s["renderer"]])
    xs = range(len(labels))
    for off, key, alpha, hatch, label in ((-0.26, "render", 1.0, None, "render phase"),
                                          (0.0, "wall", 0.45, None, "process wall"),
                                          (0.26, "cpu", 0.7, "//", "process CPU")):
        ax2.bar([x + off for x in xs], ups[key], 0.26, color=cols, alpha=alpha, hatch=hatch, label=label)
        for x, v in zip(xs, ups[key]):
            ax2.text(x + off, v, "%.2f" % v, ha="center", va="bottom", fontsize=6)
    ax2.axhline(1.0, color="black", linewidth=0.8)
    ax2.set_xticks(list(xs))
    ax2.set_xticklabels(labels, fontsize=7, rotation=30, ha="right")
    ax2.set_ylabel("kiln speed-up (peer / kiln)")
    ax2.set_title("kiln speed-up")
    ax2.legend(fontsize=7)
    fig.tight_layout()
    path = os.path.join(folder, "chart.png")
    fig.savefig(path, dpi=80)
    return path


def to_png(exr, png):
    tool = os.path.join(ROOT, "tools", "exr_to_png.py")
    if os.path.isfile(exr) and shutil.which("oiiotool"):
        subprocess.run([sys.executable, tool, exr, png], check=False, capture_output=True)
        return os.path.isfile(png)
    return False


def side_by_side(pngs, out):
    if len(pngs) >= 2 and shutil.which("oiiotool"):
        subprocess.run(["oiiotool", *pngs, "--mosaic", "%dx1" % len(pngs), "-o", out], check=False,
                       capture_output=True)


def machine_info(args, versions):
    cpu = "unknown"
    try:
        with open("/proc/cpuinfo", encoding="utf-8") as f:
            cpu = next(l.split(":", 1)[1].strip() for l in f if l.startswith("model name"))
    except (OSError, StopIteration):
        pass
    info = {"cpu": cpu, "cores": os.cpu_count(), "os": platform.platform(), "threads": args.threads}
    info.update(versions)
    return info


def version_of(cmd, pattern):
    try:
        p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=120)
    except (OSError, subprocess.TimeoutExpired):
        return None
    m = re.search(pattern, p.stdout)
    return m.group(0) if m else p.stdout.strip().splitlines()[0] if p.stdout.strip() else None


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--kiln", default=os.path.join(ROOT, "build", "renderer", "app", "kiln"))
    ap.add_argument("--blender", default=shutil.which("blender") or "blender")
    ap.add_argument("--povray", default=shutil.which("povray") or "povray")
    ap.add_argument("--out", default=os.path.join(ROOT, "build", "bench-results", "peers"))
    ap.add_argument("--assets", default=os.path.normpath(os.path.join(ROOT, "..", "shared", "assets")))
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--width", type=int, default=640)
    ap.add_argument("--height", type=int, default=480)
    ap.add_argument("--spp", type=int, default=16, help="samples per pixel (a square number for POV-Ray's +R)")
    ap.add_argument("--cases", default="toycar-16spp,quadrics-16spp,quadrics-1spp,helmet-env-16spp,"
                    "helmet-env-1pair-16spp,toycar-env-16spp,toycar-env-1pair-16spp")
    ap.add_argument("--renderers", default=",".join(RENDERERS))
    ap.add_argument("--quick", action="store_true", help="320x240, 1 round: a check that everything runs")
    ap.add_argument("--from-runs", metavar="RUNS_JSON", help="rewrite the tables and chart in --out from an "
                    "earlier runs.json, rendering nothing")
    args = ap.parse_args()
    if args.from_runs:
        with open(args.from_runs, encoding="utf-8") as f:
            old = json.load(f)
        os.makedirs(args.out, exist_ok=True)
        summary = summarise(old["runs"])
        with open(os.path.join(args.out, "summary.json"), "w", encoding="utf-8") as f:
            json.dump({"meta": old["meta"], "summary": summary}, f, indent=1)
        print(write_tables(summary, args.out, old["meta"]))
        write_chart(summary, args.out)
        return
    if args.quick:
        args.width, args.height, args.rounds = 320, 240, 1
    if not os.access(args.kiln, os.X_OK):
        sys.exit("peer_bench.py: %s: no kiln executable (build the kiln target, or give --kiln)" % args.kiln)
    folder = os.path.abspath(args.out)
    os.makedirs(os.path.join(folder, "images"), exist_ok=True)
    os.makedirs(os.path.join(folder, "work"), exist_ok=True)
    work = os.path.join(folder, "work")

    wanted = args.renderers.split(",")
    skipped = []
    have = {"kiln": True}
    for name, path in (("cycles", args.blender), ("povray", args.povray)):
        have[name] = name in wanted and shutil.which(path) is not None
        if name in wanted and not have[name]:
            skipped.append("%s: %s is not installed" % (name, path))
            log("skipping", name + ":", path, "is not installed")
    versions = {"kiln": version_of([args.kiln, "--version"], r".+"), "kiln binary": os.path.abspath(args.kiln),
                "benchmark script commit": version_of(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"], r"\w+")}
    if have.get("cycles"):
        versions["blender"] = version_of([args.blender, "-b", "--factory-startup", "--version"], r"Blender [\d.]+")
    if have.get("povray"):
        versions["povray"] = version_of([args.povray, "--version"], r"POV-Ray [\w.]+")

    pov = os.path.join(HERE, "peer_quadrics.pov")
    quadrics = os.path.join(ROOT, "scenes", "peer_quadrics.gltf")
    cases = []
    for name in args.cases.split(","):
        spp = 1 if name.endswith("-1spp") else args.spp
        if "-env" in name:
            key = name.split("-env")[0]
            asset = os.path.join(args.assets, *ENVIRONMENT_ASSETS[key]) if key in ENVIRONMENT_ASSETS else None
            if not asset or not os.path.isfile(asset):
                skipped.append("%s: asset not found under %s" % (name, args.assets))
                continue
            kiln_args = ["--lighting", "studio"] + (["--environment-samples", "1"] if "-1pair" in name else [])
            cases.append({"name": name, "gltf": asset, "spp": spp, "renderers": ["kiln", "cycles"],
                          "kiln_args": kiln_args,
                          "environment": os.path.join(ROOT, "share", "environments", "studio.exr"),
                          "camera_json": environment_case(args, key, asset, work, args.width, args.height)})
            skipped.append("%s: POV-Ray reads no glTF" % name)
        elif name.startswith("toycar"):
            asset = find_toycar(args.assets)
            if not asset:
                skipped.append("%s: ToyCar not found under %s" % (name, args.assets))
                continue
            cases.append({"name": name, "gltf": toycar_wrapper(asset, work, args.width, args.height), "outside": True,
                          "spp": spp, "renderers": ["kiln", "cycles"], "kiln_args": FILE_LIGHTS_ONLY})
            skipped.append("%s: POV-Ray reads no glTF" % name)
        elif name.startswith("quadrics"):
            cases.append({"name": name, "gltf": quadrics, "pov": pov, "spp": spp, "renderers": ["kiln", "povray"],
                          "kiln_args": FILE_LIGHTS_ONLY})
            skipped.append("%s: Cycles has no analytic quadrics (KILN_quadric)" % name)
        else:
            sys.exit("peer_bench.py: unknown case %r" % name)
        cases[-1].update({"width": args.width, "height": args.height})

    runners = {"kiln": run_kiln, "cycles": run_cycles, "povray": run_povray}
    runs = []
    for rnd in range(1, args.rounds + 1):
        for case in cases:
            for renderer in RENDERERS:
                if renderer not in case["renderers"] or renderer not in wanted or not have.get(renderer):
                    continue
                stem = "%s-%s" % (case["name"], renderer)
                exr = os.path.join(work, stem + ".exr")
                load_before = os.getloadavg()[0]
                row = runners[renderer](args, case, exr, os.path.join(work, stem + ".log"))
                row.update({"case": case["name"], "renderer": renderer, "round": rnd, "load_avg_1min_before": load_before})
                runs.append(row)
                log("round %d %-15s %-7s render %.3f s, wall %.3f s (load %.2f)" % (
                    rnd, case["name"], renderer, row["render_s"] or float("nan"), row["wall_s"], load_before))

    pngs = {}
    for case in cases:
        pngs[case["name"]] = []
        for renderer in RENDERERS:
            exr = os.path.join(work, "%s-%s.exr" % (case["name"], renderer))
            png = os.path.join(folder, "images", "%s-%s.png" % (case["name"], renderer))
            if os.path.isfile(exr) and to_png(exr, png):
                pngs[case["name"]].append(png)
        side_by_side(pngs[case["name"]], os.path.join(folder, "images", "%s-side-by-side.png" % case["name"]))

    summary = summarise(runs)
    meta = {"rounds": args.rounds, "machine": machine_info(args, versions), "skipped": skipped,
            "settings": "%dx%d, %d threads, %d spp (1 for the -1spp case); kiln --max-depth 8; Cycles Whitted-like "
                        "(bench/peers/blender_render.py; the -env cases: bench/peers/blender_environment.py); "
                        "POV-Ray +A0.0 +AM1 +R%d (-A at 1 spp), max_trace_level 9."
                        % (args.width, args.height, args.threads, args.spp, int(round(math.sqrt(args.spp)))),
            "load_avg_after": os.getloadavg()}
    loads = [r["load_avg_1min_before"] for r in runs]
    meta["load_range"] = "%.2f to %.2f" % (min(loads), max(loads)) if loads else "?"
    with open(os.path.join(folder, "runs.json"), "w", encoding="utf-8") as f:
        json.dump({"meta": meta, "runs": runs}, f, indent=1)
    with open(os.path.join(folder, "summary.json"), "w", encoding="utf-8") as f:
        json.dump({"meta": meta, "summary": summary}, f, indent=1)
    print(write_tables(summary, folder, meta))
    chart = write_chart(summary, folder)
    log("results in", folder, "(chart: %s)" % (chart or "none"))


if __name__ == "__main__":
    main()
