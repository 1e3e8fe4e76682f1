#!/usr/bin/python3
"""The energy of point-light highlights on smooth metal: kiln against Blender Cycles.
A measurement, never a test: nothing here asserts a number.

kiln widens a punctual light's GGX lobe to the pixel footprint (shade/material_eval.h,
highlight_footprint_alpha) so that near-mirror highlights converge; the widening must move the
highlight's light around, never add or remove it. This script renders one point light on smooth
metal (base colour 0.9, metallic 1) and sums the highlight over the whole image:

  kiln:   the `direct` AOV (light reaching the camera's first surface straight from the lamp, no
          mirror rays), `kiln render --lighting file --aovs beauty,direct --float`;
  Cycles: bench/peers/blender_render.py with --glossy-bounces 0 (direct light alone), point light
          of radius 0 and power 4 pi I, box filter one pixel wide.

Meshes (written to OUT/, each with its camera and lamp):
  suzanne       the shipped Suzanne's triangles and vertex normals (smooth-shaded, 3936 triangles:
                low-poly for a curved surface), textures dropped;
  sphere        a UV sphere of 192 x 96 quads (tessellated: its vertex normals barely turn per
                triangle).
A creased low-poly mesh is held to its energy by tests/shading_corrections_test.cpp (kiln at two
resolutions).

Prints a Markdown table of image sums kiln / Cycles at each size and roughness and writes it to
OUT/tables.md (every number also to OUT/results.json).

Usage:
  /usr/bin/python3 bench/peers/highlight_compare.py [--kiln build/renderer/app/kiln]
      [--out build/bench-results/highlight] [--assets ../shared/assets] [--meshes suzanne,sphere]
      [--roughness 0.1,0.2] [--sizes 320x240,960x720] [--kiln-spp 256] [--cycles-spp 1024] [--threads 2]

Needs: Blender with Cycles (Debian 12's `blender`, 3.4) and its glTF importer, python3-numpy and
python3-openimageio. About 25 minutes on 2 idle cores with the defaults (Cycles at 960x720 and
1024 spp is most of it).
"""

import argparse
import base64
import json
import math
import os
import shutil
import struct
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))
sys.path.insert(0, HERE)
from environment_compare import read_exr, run  # noqa: E402

BLENDER_SCRIPT = os.path.join(HERE, "blender_render.py")

# Camera on +Z looking at the origin, one lamp up and to the right (glTF units, candela).
CAMERA_Z = 4.0
CAMERA_YFOV = 0.6
LAMP = [1.5, 2.0, 3.0]
LAMP_INTENSITY = 20.0


def log(*parts):
    print("highlight_compare:", *parts, file=sys.stderr, flush=True)


def metal(roughness):
    return {"pbrMetallicRoughness": {"baseColorFactor": [0.9, 0.9, 0.9, 1.0], "metallicFactor": 1.0,
                                     "roughnessFactor": roughness}}


def with_camera_and_lamp(g):
    """g with a perspective camera at (0, 0, CAMERA_Z) looking down -Z and one point lamp."""
    g.setdefault("extensionsUsed", []).append("KHR_lights_punctual")
    g["extensions"] = {"KHR_lights_punctual": {"lights": [
        {"name": "lamp", "type": "point", "intensity": LAMP_INTENSITY, "color": [1, 1, 1]}]}}
    g["cameras"] = [{"type": "perspective", "perspective": {"yfov": CAMERA_YFOV, "znear": 0.01, "aspectRatio": 4 / 3}}]
    base = len(g["nodes"])
    g["nodes"] += [{"name": "camera", "camera": 0, "translation": [0.0, 0.0, CAMERA_Z]},
                   {"name": "lamp", "translation": LAMP, "extensions": {"KHR_lights_punctual": {"light": 0}}}]
    g["scenes"][0]["nodes"] += [base, base + 1]
    return g


def mesh_gltf(positions, normals, indices, material):
    """A one-primitive glTF of float positions and normals (flat lists) and uint32 indices."""
    blob = struct.pack("<%df" % len(positions), *positions) + struct.pack("<%df" % len(normals), *normals) + \
        struct.pack("<%dI" % len(indices), *indices)
    n = len(positions) // 3
    p = np.asarray(positions, dtype=np.float64).reshape(-1, 3)
    return {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
            "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2, "material": 0}]}],
            "materials": [material],
            "buffers": [{"byteLength": len(blob),
                         "uri": "data:application/octet-stream;base64," + base64.b64encode(blob).decode()}],
            "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 12 * n},
                            {"buffer": 0, "byteOffset": 12 * n, "byteLength": 12 * n},
                            {"buffer": 0, "byteOffset": 24 * n, "byteLength": 4 * len(indices)}],
            "accessors": [{"bufferView": 0, "componentType": 5126, "count": n, "type": "VEC3",
                           "min": p.min(axis=0).tolist(), "max": p.max(axis=0).tolist()},
                          {"bufferView": 1, "componentType": 5126, "count": n, "type": "VEC3"},
                          {"bufferView": 2, "componentType": 5125, "count": len(indices), "type": "SCALAR"}]}


def uv_sphere(rings, segments):
    """A unit UV sphere: flat lists of positions and normals (the same), triangle indices."""
    pos, idx = [], []
    for i in range(rings + 1):
        t = math.pi * i / rings
        for j in range(segments + 1):
            p = 2 * math.pi * j / segments
            pos.append((math.sin(t) * math.cos(p), math.cos(t), -math.sin(t) * math.sin(p)))
    for i in range(rings):
        for j in range(segments):
            a, b = i * (segments + 1) + j, (i + 1) * (segments + 1) + j
            idx += [a, b, a + 1, a + 1, b, b + 1]
    flat = [c for v in pos for c in v]
    return flat, list(flat), idx


def write_suzanne(path, assets, roughness):
    """Suzanne's triangles and normals (accessors 0-2 of the shipped file) under a metal."""
    src = os.path.join(assets, "Suzanne", "glTF")
    with open(os.path.join(src, "Suzanne.gltf"), encoding="utf-8") as f:
        g = json.load(f)
    shutil.copyfile(os.path.join(src, "Suzanne.bin"), os.path.join(os.path.dirname(path), "Suzanne.bin"))
    prim = g["meshes"][0]["primitives"][0]
    prim["attributes"] = {"POSITION": prim["attributes"]["POSITION"], "NORMAL": prim["attributes"]["NORMAL"]}
    g["materials"] = [metal(roughness)]
    for key in ("textures", "images", "samplers"):
        g.pop(key, None)
    with open(path, "w", encoding="utf-8") as f:
        json.dump(with_camera_and_lamp(g), f)


def write_sphere(path, roughness):
    with open(path, "w", encoding="utf-8") as f:
        json.dump(with_camera_and_lamp(mesh_gltf(*uv_sphere(96, 192), metal(roughness))), f)


WRITERS = {"suzanne": lambda path, args, r: write_suzanne(path, args.assets, r),
           "sphere": lambda path, args, r: write_sphere(path, r)}


def rgb_sum(path, layer=None):
    """Sum of R + G + B over the image (kiln's `direct` AOV when layer is 'direct')."""
    pixels, names, _ = read_exr(path)
    want = ("R", "G", "B") if layer is None else tuple("%s.%s" % (layer, c) for c in ("R", "G", "B"))
    index = [names.index(c) for c in want]
    return float(pixels[:, :, index].astype(np.float64).sum())


def kiln_highlight(args, scene, out_exr, width, height):
    cmd = [args.kiln, "render", scene, "-o", out_exr, "--width", str(width), "--height", str(height),
           "--spp", str(args.kiln_spp), "--threads", str(args.threads), "--lighting", "file", "--float",
           "--aovs", "beauty,direct"]
    run(cmd, out_exr[:-4] + ".log")
    return rgb_sum(out_exr, "direct"), " ".join(["kiln"] + cmd[1:])


def cycles_highlight(args, scene, out_exr, width, height):
    cmd = [args.blender, "-b", "--factory-startup", "-noaudio", "-t", str(args.threads), "--python", BLENDER_SCRIPT,
           "--", scene, out_exr, out_exr[:-4] + ".stats.json", "--width", str(width), "--height", str(height),
           "--spp", str(args.cycles_spp), "--threads", str(args.threads), "--glossy-bounces", "0", "--float"]
    run(cmd, out_exr[:-4] + ".log")
    return rgb_sum(out_exr), " ".join(["blender"] + cmd[1:])


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--kiln", default=os.path.join(ROOT, "build", "renderer", "app", "kiln"))
    p.add_argument("--blender", default="blender")
    p.add_argument("--out", default=os.path.join(ROOT, "build", "bench-results", "highlight"))
    p.add_argument("--assets", default=os.path.normpath(os.path.join(ROOT, "..", "shared", "assets")))
    p.add_argument("--meshes", default="suzanne,sphere")
    p.add_argument("--roughness", default="0.1,0.2")
    p.add_argument("--sizes", default="320x240,960x720")
    p.add_argument("--kiln-spp", type=int, default=256)
    p.add_argument("--cycles-spp", type=int, default=1024)
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--no-cycles", action="store_true", help="kiln's sums only (Cycles' from an earlier results.json)")
    args = p.parse_args()
    os.makedirs(args.out, exist_ok=True)
    results_path = os.path.join(args.out, "results.json")
    earlier = {}
    if os.path.exists(results_path):
        with open(results_path, encoding="utf-8") as f:
            earlier = {(r["mesh"], r["roughness"], r["size"]): r for r in json.load(f)}
    rows = []
    for mesh in args.meshes.split(","):
        for roughness in (float(r) for r in args.roughness.split(",")):
            scene = os.path.join(args.out, "%s-r%g.gltf" % (mesh, roughness))
            WRITERS[mesh](scene, args, roughness)
            for size in args.sizes.split(","):
                width, height = (int(v) for v in size.split("x"))
                stem = os.path.join(args.out, "%s-r%g-%s" % (mesh, roughness, size))
                log(mesh, roughness, size)
                k, k_cmd = kiln_highlight(args, scene, stem + "-kiln.exr", width, height)
                old = earlier.get((mesh, roughness, size))
                if args.no_cycles and old:
                    c, c_cmd = old["cycles"], old["cycles_command"]
                else:
                    c, c_cmd = cycles_highlight(args, scene, stem + "-cycles.exr", width, height)
                rows.append({"mesh": mesh, "roughness": roughness, "size": size, "kiln": k, "cycles": c,
                             "ratio": k / c, "kiln_command": k_cmd, "cycles_command": c_cmd})
                log("  kiln %.4g cycles %.4g ratio %.4f" % (k, c, k / c))
    with open(results_path, "w", encoding="utf-8") as f:
        json.dump(rows, f, indent=1)
    lines = ["| mesh | roughness | size | kiln %d spp | Cycles %d spp | kiln / Cycles |" % (args.kiln_spp, args.cycles_spp),
             "|---|---|---|---|---|---|"]
    for r in rows:
        lines.append("| %s | %g | %s | %.4g | %.4g | %.4f |" % (r["mesh"], r["roughness"], r["size"], r["kiln"],
                                                               r["cycles"], r["ratio"]))
    text = "\n".join(lines) + "\n"
    with open(os.path.join(args.out, "tables.md"), "w", encoding="utf-8") as f:
        f.write(text)
    print(text)


if __name__ == "__main__":
    main()
