#!/usr/bin/python3
"""kiln's environment lighting against Blender Cycles with the same equirectangular map as its World.
A measurement, never a test: nothing here asserts a number.

kiln renders with `--lighting studio` (share/environments/studio.exr alone, the file's lights off;
`--environment MAP` gives `--lighting file --environment MAP`), Cycles through
bench/peers/blender_environment.py: the same EXR as an Environment Texture World turned to kiln's
orientation, diffuse bounces 0, glossy and transmission bounces 8, no caustics, box filter one
pixel wide, transparent film, the file's lights and cameras deleted, and kiln's own camera, built
from the worldToCamera and worldToNDC attributes kiln writes into its EXR (glTF's +Y up turned
into Blender's +Z up as the glTF importer turns it). Three tables:

  1. one sphere under the map (no interreflection, so Whitted and path tracing see the same light),
     one material lobe at a time: mean radiance kiln / Cycles with the importer's Principled BSDF
     and with glTF's BRDF built from Cycles nodes (blender_environment.py --material gltf), and
     for the Lambert sphere both against the closed form (albedo / pi x the map's irradiance).
  2. shipped assets at --ref-spp (--noise-ref-spp for --noise-assets): mean radiance per channel
     over the pixels both cover fully (alpha > 0.999), kiln / Cycles, with the importer's
     materials, with glTF's BRDF, and with glTF's BRDF and glossy bounces 0 (no glossy
     interreflection; Cycles' mirrors then see only the map); per-pixel RMSE over Cycles' mean.
  3. noise against samples on --noise-assets: kiln at 1, 4, 16, 64 spp against its own reference
     and Cycles' (per-pixel RMSE over the reference's mean), and Cycles at the same counts against
     its own reference, rendered with another seed (kiln's samples are seeded by their camera ray,
     which differs between sample counts);
  4. time at equal samples (Cycles with the importer's materials): render phase (kiln's; Cycles'
     render_pre..render_post: sync, BVH, sampling) and process wall, at --time-spp, the sweep's
     counts and the references'.

Prints Markdown tables and writes them to OUT/tables.md, every number to OUT/results.json, and
kiln | Cycles (glTF BRDF) | |difference| x4 PNGs to OUT/images/.
`--check-orientation` instead renders a mirror ball under a map of three coloured spots with the
World turned by -90, 0, 90 and 180 degrees, background shown, and prints each turn's RMSE against
kiln: the turn blender_environment.py uses (-90) is the one with the smallest.

Usage:
  /usr/bin/python3 bench/peers/environment_compare.py [--kiln build/renderer/app/kiln]
      [--out build/bench-results/environment] [--assets ../shared/assets] [--quick]
      [--width 240 --height 180 --threads 2 --ref-spp 128 --noise-ref-spp 1024 --time-spp 16]
  /usr/bin/python3 bench/peers/environment_compare.py --check-orientation

Needs: Blender with Cycles (Debian 12's `blender`, 3.4, and its glTF importer), python3-numpy and
python3-openimageio. About 6 minutes on 2 idle cores with the defaults, 2 with --quick.
"""

import argparse
import json
import math
import os
import re
import shutil
import subprocess
import sys
import time

import numpy as np
import OpenImageIO as oiio

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))
STUDIO = os.path.join(ROOT, "share", "environments", "studio.exr")
BLENDER_SCRIPT = os.path.join(HERE, "blender_environment.py")

# name: (path under the assets folder or the repository, what it shows)
ASSETS = {
    "Avocado": ("Avocado/glTF/Avocado.gltf", "convex, textured dielectric, rough"),
    "DamagedHelmet": ("DamagedHelmet/glTF-Binary/DamagedHelmet.glb", "textured metal and dielectric, emissive, self-occluding"),
    "MetalRoughSpheresNoTextures": ("MetalRoughSpheresNoTextures/glTF-Binary/MetalRoughSpheresNoTextures.glb",
                                    "spheres from smooth to rough, metal and dielectric"),
    "Suzanne": ("Suzanne/glTF/Suzanne.gltf", "dark textured dielectric, concave (eyes, ears)"),
    "SheenCloth": ("SheenCloth/glTF/SheenCloth.gltf", "KHR_materials_sheen (Cycles' own sheen model)"),
    "ToyCar": ("ToyCar/glTF/ToyCar.gltf", "clearcoat, sheen, glass; its own camera"),
    "glass_showcase": ("scenes/glass_showcase.gltf", "mirror and glass spheres, glass slab and pane on a floor"),
}
DEFAULT_ASSETS = "Avocado,DamagedHelmet,MetalRoughSpheresNoTextures,Suzanne,SheenCloth,ToyCar,glass_showcase"
DEFAULT_NOISE_ASSETS = "Avocado,DamagedHelmet"

KILN_SUMMARY = re.compile(r"load ([\d.]+) s, build ([\d.]+) s, render ([\d.]+) s")


def log(*parts):
    print("environment_compare:", *parts, file=sys.stderr, flush=True)


# ---- images ------------------------------------------------------------------------------------

def read_exr(path):
    """(H x W x C float32 pixels, channel names, {attribute: value}) of the first part."""
    inp = oiio.ImageInput.open(path)
    if inp is None:
        raise RuntimeError("cannot read %s: %s" % (path, oiio.geterror()))
    spec = inp.spec()
    pixels = inp.read_image(0, 0, 0, spec.nchannels, oiio.FLOAT)
    inp.close()
    attrs = {a.name: a.value for a in spec.extra_attribs}
    return np.asarray(pixels, dtype=np.float32).reshape(spec.height, spec.width, spec.nchannels), \
        list(spec.channelnames), attrs


def rgba(path):
    pixels, names, _ = read_exr(path)
    index = [names.index(c) for c in ("R", "G", "B", "A")]
    return pixels[:, :, index]


def to_png(rgb, path, alpha=None):
    """Linear RGB (premultiplied, over black where alpha is given) to an 8-bit sRGB PNG."""
    x = np.clip(np.nan_to_num(rgb), 0.0, None)
    x = np.where(x <= 0.0031308, 12.92 * x, 1.055 * np.power(np.minimum(x, 1.0), 1.0 / 2.4) - 0.055)
    x = np.clip(x, 0.0, 1.0)
    if alpha is not None:
        x = np.concatenate([x, np.clip(alpha, 0.0, 1.0)[:, :, None]], axis=2)
    out = oiio.ImageOutput.create(path)
    spec = oiio.ImageSpec(x.shape[1], x.shape[0], x.shape[2], oiio.UINT8)
    out.open(path, spec)
    if not out.write_image(np.ascontiguousarray(x * 255.0 + 0.5, dtype=np.uint8)):
        raise RuntimeError("cannot write %s: %s" % (path, out.geterror()))
    out.close()


# ---- camera ------------------------------------------------------------------------------------

# glTF (x, y, z) -> Blender (x, -z, y), as Blender's glTF importer converts +Y up to +Z up.
GLTF_TO_BLENDER = np.array([[1, 0, 0], [0, 0, -1], [0, 1, 0]], dtype=np.float64)


def blender_camera(attrs, width, height):
    """Blender's camera (matrix_world in Blender's frame, vertical fov) from kiln's EXR attributes.

    worldToCamera is OpenEXR's (stored for row vectors): camera space +X right, +Y up, +Z forward.
    A Blender camera looks along its local -Z with +Y up. worldToNDC gives the field of view: NDC
    y runs from 0 at the top to 1 at the bottom, so its slope over y/z is 0.5 / tan(yfov / 2).
    """
    w2c = np.array(attrs["worldToCamera"], dtype=np.float64).reshape(4, 4).T
    w2n = np.array(attrs["worldToNDC"], dtype=np.float64).reshape(4, 4).T
    c2w = np.linalg.inv(w2c)
    c2n = w2n @ c2w
    if abs(c2n[3, 2]) < 1e-12:
        raise RuntimeError("orthographic camera: not compared")
    tan_y = 0.5 / abs(c2n[1, 1] / c2n[3, 2])
    tan_x = 0.5 / abs(c2n[0, 0] / c2n[3, 2])
    centre = (c2n[0, 2] / c2n[3, 2], c2n[1, 2] / c2n[3, 2])
    if abs(tan_x / tan_y - width / height) > 1e-3 * width / height or max(abs(centre[0] - 0.5), abs(centre[1] - 0.5)) > 1e-4:
        raise RuntimeError("camera window is not centred or its aspect is not the image's: %r %r" % (tan_x / tan_y, centre))
    right, up, forward, eye = c2w[:3, 0], c2w[:3, 1], c2w[:3, 2], c2w[:3, 3]
    m = np.eye(4)
    m[:3, 0] = GLTF_TO_BLENDER @ (right / np.linalg.norm(right))
    m[:3, 1] = GLTF_TO_BLENDER @ (up / np.linalg.norm(up))
    m[:3, 2] = GLTF_TO_BLENDER @ (-forward / np.linalg.norm(forward))
    m[:3, 3] = GLTF_TO_BLENDER @ eye
    distance = float(np.linalg.norm(eye))
    return {"matrix_world": m.tolist(), "yfov": 2.0 * math.atan(tan_y), "clip_start": max(1e-5, 1e-5 * distance)}


# ---- renderers ---------------------------------------------------------------------------------

def run(cmd, log_path):
    t0 = time.perf_counter()
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, errors="replace")
    wall = time.perf_counter() - t0
    with open(log_path, "w", encoding="utf-8") as f:
        f.write(" ".join(cmd) + "\n" + p.stdout)
    if p.returncode != 0:
        raise RuntimeError("%s failed (exit %d): %s" % (os.path.basename(cmd[0]), p.returncode, p.stdout[-2000:]))
    return wall, p.stdout


def run_kiln(args, asset, out_exr, spp, extra=()):
    """kiln lit by the environment alone; returns {render_s, wall_s, load_s, build_s}."""
    cmd = [args.kiln, "render", asset, "-o", out_exr, "--width", str(args.width), "--height", str(args.height),
           "--spp", str(spp), "--threads", str(args.threads), "--float", "--aovs", "beauty"]
    cmd += ["--lighting", "file", "--environment", args.environment] if args.environment != STUDIO else ["--lighting", "studio"]
    cmd += list(extra)
    wall, text = run(cmd, out_exr[:-4] + ".log")
    m = KILN_SUMMARY.search(text)
    if not m:
        raise RuntimeError("no kiln summary line in: " + text[-500:])
    return {"wall_s": wall, "load_s": float(m.group(1)), "build_s": float(m.group(2)), "render_s": float(m.group(3))}


def run_cycles(args, asset, out_exr, camera, spp, seed=0, extra=()):
    """Cycles through kiln's camera under the same map; returns {render_s, wall_s, import_s}."""
    cam_json = out_exr[:-4] + ".camera.json"
    stats = out_exr[:-4] + ".stats.json"
    with open(cam_json, "w", encoding="utf-8") as f:
        json.dump(camera, f)
    cmd = [args.blender, "-b", "--factory-startup", "-noaudio", "-t", str(args.threads), "--python", BLENDER_SCRIPT,
           "--", asset, out_exr, stats, "--environment", args.environment, "--camera", cam_json,
           "--width", str(args.width), "--height", str(args.height), "--spp", str(spp),
           "--threads", str(args.threads), "--seed", str(seed), *extra]
    wall, _ = run(cmd, out_exr[:-4] + ".log")
    with open(stats, encoding="utf-8") as f:
        s = json.load(f)
    return {"wall_s": wall, "render_s": s["render_s"], "import_s": s["import_s"], "blender": s["blender"]}


# ---- measures ----------------------------------------------------------------------------------

def covered(*images):
    """Pixels every image covers fully (alpha > 0.999): edges, where box filters of two renderers
    cut a silhouette differently, are left out."""
    mask = np.ones(images[0].shape[:2], dtype=bool)
    for im in images:
        mask &= im[:, :, 3] > 0.999
    return mask


def mean_rgb(im, mask):
    return im[mask][:, :3].mean(axis=0)


def rmse(a, b, mask):
    d = a[mask][:, :3] - b[mask][:, :3]
    return float(np.sqrt(np.mean(d * d)))


def luminance(rgb):
    return float(0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2])


def side_by_side(kiln_im, cycles_im, path):
    diff = np.abs(kiln_im[:, :, :3] - cycles_im[:, :, :3]) * 4.0
    row = np.concatenate([kiln_im[:, :, :3], cycles_im[:, :, :3], diff], axis=1)
    to_png(row, path)


def asset_path(args, name):
    rel = ASSETS[name][0]
    return os.path.join(ROOT, rel) if rel.startswith("scenes/") else os.path.join(args.assets, rel)


# ---- orientation check -------------------------------------------------------------------------

def write_spot_map(path, width=256, height=128):
    """A dim grey map with three spots, kiln's (u, v): red along +X 20 degrees up (0.75, 0.39),
    green along -Z at the horizon (0.5, 0.5), blue along +Z 45 degrees up (0.0/1.0, 0.25)."""
    v, u = np.meshgrid((np.arange(height) + 0.5) / height, (np.arange(width) + 0.5) / width, indexing="ij")
    phi, theta = (u - 0.5) * 2 * math.pi, v * math.pi
    d = np.stack([np.sin(theta) * np.sin(phi), np.cos(theta), -np.sin(theta) * np.cos(phi)], axis=-1)
    img = np.full((height, width, 3), 0.05, dtype=np.float32)
    for axis, colour in (((1, 0.364, 0), (8, 0, 0)), ((0, 0, -1), (0, 8, 0)), ((0, 0.707, 0.707), (0, 0, 8))):
        a = np.array(axis) / np.linalg.norm(axis)
        img[(d @ a) > math.cos(math.radians(12))] = colour
    out = oiio.ImageOutput.create(path)
    out.open(path, oiio.ImageSpec(width, height, 3, oiio.FLOAT))
    out.write_image(img)
    out.close()


def write_sphere(path, material=None, rings=48, segments=96):
    """A smooth UV sphere of radius 1 at the origin; material: a glTF material (default: a white
    mirror, metallic 1, roughness 0)."""
    pos, nrm, idx = [], [], []
    for i in range(rings + 1):
        t = math.pi * i / rings
        for j in range(segments + 1):
            p = 2 * math.pi * j / segments
            n = (math.sin(t) * math.cos(p), math.cos(t), math.sin(t) * math.sin(p))
            pos += n
            nrm += n
    for i in range(rings):
        for j in range(segments):
            a, b = i * (segments + 1) + j, (i + 1) * (segments + 1) + j
            idx += [a, a + 1, b, b, a + 1, b + 1]
    import base64
    import struct
    blob = struct.pack("<%df" % len(pos), *pos) + struct.pack("<%df" % len(nrm), *nrm) + struct.pack("<%dI" % len(idx), *idx)
    n = len(pos) // 3
    g = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
         "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2, "material": 0}]}],
         "materials": [material or {"pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 1], "metallicFactor": 1,
                                                             "roughnessFactor": 0}}],
         "buffers": [{"byteLength": len(blob), "uri": "data:application/octet-stream;base64," + base64.b64encode(blob).decode()}],
         "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 12 * n},
                         {"buffer": 0, "byteOffset": 12 * n, "byteLength": 12 * n},
                         {"buffer": 0, "byteOffset": 24 * n, "byteLength": 4 * len(idx)}],
         "accessors": [{"bufferView": 0, "componentType": 5126, "count": n, "type": "VEC3", "min": [-1, -1, -1], "max": [1, 1, 1]},
                       {"bufferView": 1, "componentType": 5126, "count": n, "type": "VEC3"},
                       {"bufferView": 2, "componentType": 5125, "count": len(idx), "type": "SCALAR"}]}
    if material and "extensions" in material:
        g["extensionsUsed"] = sorted(material["extensions"])
    with open(path, "w", encoding="utf-8") as f:
        json.dump(g, f)


def check_orientation(args):
    work = args.out
    os.makedirs(work, exist_ok=True)
    spots, ball = os.path.join(work, "spots.exr"), os.path.join(work, "mirror_ball.gltf")
    write_spot_map(spots)
    write_sphere(ball)
    args.environment = spots
    args.width, args.height = 160, 120
    k_exr = os.path.join(work, "orient-kiln.exr")
    run_kiln(args, ball, k_exr, 16, ["--show-background", "--look-from", "2.2,1.2,2.6", "--look-at", "0,0,0", "--fov", "60"])
    k, _, attrs = read_exr(k_exr)
    camera = blender_camera(attrs, args.width, args.height)
    rows = []
    for turn in (-90, 0, 90, 180):
        c_exr = os.path.join(work, "orient-cycles%+d.exr" % turn)
        run_cycles(args, ball, c_exr, camera, 16, extra=["--map-turn", str(turn), "--show-background"])
        c = rgba(c_exr)
        mask = np.ones(k.shape[:2], dtype=bool)
        rows.append((turn, rmse(k, c, mask), mean_rgb(k, mask) / np.maximum(mean_rgb(c, mask), 1e-9)))
        side_by_side(k, c, os.path.join(work, "orient%+d.png" % turn))
    print("| World turn about Blender +Z | RMSE kiln - Cycles (background and mirror ball) | mean ratio kiln/Cycles (R, G, B) |")
    print("|---|---|---|")
    for turn, e, ratio in rows:
        print("| %+d deg | %.4f | %s |" % (turn, e, ", ".join("%.3f" % r for r in ratio)))
    print("\nimages: %s/orient*.png (kiln | Cycles | |difference| x4)" % work)


# ---- single spheres: where the models agree -----------------------------------------------------

def material(base, metallic, roughness, specular=None):
    m = {"pbrMetallicRoughness": {"baseColorFactor": [base, base, base, 1.0], "metallicFactor": metallic,
                                  "roughnessFactor": roughness}}
    if specular is not None:
        m["extensions"] = {"KHR_materials_specular": {"specularFactor": specular}}
    return m


# name: (glTF material, what it isolates). One sphere under the map has no interreflection: kiln's
# Whitted shading and Cycles' path tracing see the same light.
SPHERES = [
    ("Lambert 0.8 (specularFactor 0)", material(0.8, 0.0, 1.0, specular=0.0), "diffuse lobe alone"),
    ("dielectric 0.8, roughness 1", material(0.8, 0.0, 1.0), "diffuse + rough specular"),
    ("dielectric 0.8, roughness 0.5", material(0.8, 0.0, 0.5), "diffuse + glossy specular"),
    ("dielectric 0.8, roughness 0", material(0.8, 0.0, 0.0), "diffuse + mirror"),
    ("dielectric black, roughness 0.5", material(0.0, 0.0, 0.5), "dielectric specular lobe alone"),
    ("dielectric black, roughness 0", material(0.0, 0.0, 0.0), "dielectric mirror alone"),
    ("metal 0.9, roughness 1", material(0.9, 1.0, 1.0), "GGX at alpha 1"),
    ("metal 0.9, roughness 0.5", material(0.9, 1.0, 0.5), "GGX"),
    ("metal 0.9, roughness 0.2", material(0.9, 1.0, 0.2), "inside kiln's mirror fade (0 to 0.25)"),
    ("metal 0.9, roughness 0.1", material(0.9, 1.0, 0.1), "inside kiln's mirror fade"),
    ("metal 0.9, roughness 0", material(0.9, 1.0, 0.0), "perfect mirror"),
]
SPHERE_VIEW = ["--look-from", "0,0,3.2", "--look-at", "0,0,0", "--fov", "45"]


def lambert_sphere_reference(environment, width, height, albedo=0.8):
    """The radiance of a Lambert sphere (radius 1 at the origin, camera SPHERE_VIEW) at each pixel
    centre: albedo / pi x the irradiance the map gives its normal, summed over every texel (kiln's
    mapping, solid angle per texel); a sphere does not shadow itself. Returns (image, hit mask)."""
    env = read_exr(environment)[0][:, :, :3].astype(np.float64)
    h, w = env.shape[:2]
    v, u = np.meshgrid((np.arange(h) + 0.5) / h, (np.arange(w) + 0.5) / w, indexing="ij")
    phi, theta = (u - 0.5) * 2 * math.pi, v * math.pi
    dirs = np.stack([np.sin(theta) * np.sin(phi), np.cos(theta), -np.sin(theta) * np.cos(phi)], -1).reshape(-1, 3)
    power = env.reshape(-1, 3) * ((2 * math.pi / w) * (math.pi / h) * np.sin(theta)).reshape(-1, 1)
    eye, t = np.array([0.0, 0.0, 3.2]), math.tan(math.radians(45) / 2)
    ys, xs = np.meshgrid(np.arange(height) + 0.5, np.arange(width) + 0.5, indexing="ij")
    d = np.stack([(2 * xs / width - 1) * t * width / height, (1 - 2 * ys / height) * t, -np.ones_like(xs)], -1)
    d /= np.linalg.norm(d, axis=-1, keepdims=True)
    b = d @ eye
    disc = b * b - (eye @ eye - 1.0)
    hit = disc > 0.0
    normals = eye + (-b - np.sqrt(np.maximum(disc, 0.0)))[..., None] * d
    n = normals[hit]
    irradiance = np.concatenate([np.maximum(n[i:i + 512] @ dirs.T, 0.0) @ power for i in range(0, len(n), 512)])
    ref = np.zeros((height, width, 4))
    ref[hit, :3] = albedo / math.pi * irradiance
    ref[hit, 3] = 1.0
    return ref, hit


def compare_spheres(args, work, images):
    rows = []
    size = (args.width, args.height)
    args.width, args.height = 160, 120
    ref, _ = lambert_sphere_reference(args.environment, args.width, args.height)
    for i, (name, mat, isolates) in enumerate(SPHERES):
        gltf = os.path.join(work, "sphere%02d.gltf" % i)
        write_sphere(gltf, mat)
        k_exr = os.path.join(work, "sphere%02d-kiln.exr" % i)
        run_kiln(args, gltf, k_exr, args.sphere_spp, SPHERE_VIEW)
        k, _, attrs = read_exr(k_exr)
        camera = blender_camera(attrs, args.width, args.height)
        cyc = {}
        for mode in ("importer", "gltf"):
            c_exr = os.path.join(work, "sphere%02d-cycles-%s.exr" % (i, mode))
            run_cycles(args, gltf, c_exr, camera, args.sphere_spp, seed=1, extra=["--material", mode])
            cyc[mode] = rgba(c_exr)
        mask = covered(k, cyc["importer"], cyc["gltf"])
        mk = mean_rgb(k, mask).mean()
        row = {"sphere": name, "isolates": isolates, "kiln_mean": float(mk),
               "ratio_importer": float(mk / mean_rgb(cyc["importer"], mask).mean()),
               "ratio_gltf": float(mk / mean_rgb(cyc["gltf"], mask).mean()),
               "rmse_gltf": rmse(k, cyc["gltf"], mask) / float(mean_rgb(cyc["gltf"], mask).mean())}
        if "KHR_materials_specular" in json.dumps(mat):
            row["ratio_analytic"] = float(mk / mean_rgb(ref, mask).mean())
            row["cycles_gltf_vs_analytic"] = float(mean_rgb(cyc["gltf"], mask).mean() / mean_rgb(ref, mask).mean())
        rows.append(row)
        side_by_side(k, cyc["gltf"], os.path.join(images, "sphere%02d-kiln-cycles-diff.png" % i))
        log("sphere %-34s kiln/Cycles %.3f (importer) %.3f (glTF BRDF)" % (name, row["ratio_importer"], row["ratio_gltf"]))
    args.width, args.height = size
    return rows


# ---- main --------------------------------------------------------------------------------------

def fmt_ratio(r):
    return "%.3f / %.3f / %.3f" % tuple(r)


def compare_asset(args, name, asset, ref_spp, work, images):
    """Both renderers at ref_spp; Cycles with the importer's materials, with glTF's BRDF, and with
    glTF's BRDF and no glossy bounces (glossy lobes see the map directly and nothing else: no
    interreflection, which kiln's Whitted shading has only through its mirror rays)."""
    k_exr = os.path.join(work, name + "-kiln-ref.exr")
    k_time = run_kiln(args, asset, k_exr, ref_spp)
    k, _, attrs = read_exr(k_exr)
    camera = blender_camera(attrs, args.width, args.height)
    cyc, times, rewritten = {}, {}, {}
    for mode in ("importer", "gltf", "gltf-glossy0"):
        c_exr = os.path.join(work, "%s-cycles-%s-ref.exr" % (name, mode))
        extra = ["--material", mode.split("-")[0]] + (["--glossy-bounces", "0"] if mode.endswith("glossy0") else [])
        times[mode] = run_cycles(args, asset, c_exr, camera, ref_spp, seed=1, extra=extra)
        cyc[mode] = rgba(c_exr)
        with open(c_exr[:-4] + ".stats.json", encoding="utf-8") as f:
            stats = json.load(f)
        rewritten[mode] = "%d of %d" % (len(stats["rewritten"]), stats["materials"])
    mask = covered(k, cyc["importer"], cyc["gltf"], cyc["gltf-glossy0"])
    mk = mean_rgb(k, mask)
    row = {"asset": name, "shows": ASSETS[name][1], "spp": ref_spp, "pixels": int(mask.sum()),
           "kiln_mean": mk.tolist(), "kiln_ref_time": k_time, "cycles_ref_time": times["importer"],
           "rewritten": rewritten["gltf"]}
    for mode in ("importer", "gltf", "gltf-glossy0"):
        mc = mean_rgb(cyc[mode], mask)
        row["cycles_mean_" + mode] = mc.tolist()
        row["ratio_" + mode] = (mk / np.maximum(mc, 1e-12)).tolist()
        row["ratio_luminance_" + mode] = luminance(mk) / max(luminance(mc), 1e-12)
        row["rmse_rel_" + mode] = rmse(k, cyc[mode], mask) / max(float(mc.mean()), 1e-12)
    side_by_side(k, cyc["gltf"], os.path.join(images, name + "-kiln-cycles-diff.png"))
    log("%s: kiln/Cycles luminance %.3f (importer), %.3f (glTF BRDF)" % (
        name, row["ratio_luminance_importer"], row["ratio_luminance_gltf"]))
    return row, camera, k, cyc["importer"]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--kiln", default=os.path.join(ROOT, "build", "renderer", "app", "kiln"))
    ap.add_argument("--blender", default=shutil.which("blender") or "blender")
    ap.add_argument("--environment", default=STUDIO)
    ap.add_argument("--assets", default=os.path.normpath(os.path.join(ROOT, "..", "shared", "assets")))
    ap.add_argument("--out", default=os.path.join(ROOT, "build", "bench-results", "environment"))
    ap.add_argument("--cases", default=DEFAULT_ASSETS, help="assets for the mean radiance table (%s)" % ", ".join(ASSETS))
    ap.add_argument("--noise-assets", default=DEFAULT_NOISE_ASSETS)
    ap.add_argument("--width", type=int, default=240)
    ap.add_argument("--height", type=int, default=180)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--ref-spp", type=int, default=128)
    ap.add_argument("--noise-ref-spp", type=int, default=1024)
    ap.add_argument("--sphere-spp", type=int, default=128)
    ap.add_argument("--sweep", default="1,4,16,64")
    ap.add_argument("--time-spp", type=int, default=16)
    ap.add_argument("--no-spheres", action="store_true")
    ap.add_argument("--quick", action="store_true", help="160x120, references at 64 and 256 spp: does it run?")
    ap.add_argument("--check-orientation", action="store_true")
    args = ap.parse_args()
    args.out = os.path.abspath(args.out)
    args.environment = os.path.abspath(args.environment)
    if not os.access(args.kiln, os.X_OK):
        sys.exit("environment_compare.py: %s: no kiln executable" % args.kiln)
    if not shutil.which(args.blender):
        sys.exit("environment_compare.py: %s: Blender is not installed (apt-get install blender)" % args.blender)
    if args.check_orientation:
        check_orientation(args)
        return
    if args.quick:
        args.width, args.height, args.ref_spp, args.noise_ref_spp, args.sphere_spp = 160, 120, 64, 256, 64
    work = os.path.join(args.out, "work")
    images = os.path.join(args.out, "images")
    os.makedirs(work, exist_ok=True)
    os.makedirs(images, exist_ok=True)
    results = {"settings": dict(vars(args)), "machine": machine(args), "spheres": [], "assets": [], "noise": [],
               "timing": []}
    if not args.no_spheres:
        results["spheres"] = compare_spheres(args, work, images)

    cases = [c for c in args.cases.split(",") if c]
    noise_assets = [c for c in args.noise_assets.split(",") if c]
    sweep = [int(s) for s in args.sweep.split(",")]
    for name in cases + [n for n in noise_assets if n not in cases]:
        asset = asset_path(args, name)
        if not os.path.isfile(asset):
            log("skipping %s: %s not found" % (name, asset))
            continue
        ref_spp = args.noise_ref_spp if name in noise_assets else args.ref_spp
        log("%s: references at %d spp" % (name, ref_spp))
        row, camera, k, c = compare_asset(args, name, asset, ref_spp, work, images)
        results["assets"].append(row)
        for spp in (sweep if name in noise_assets else [args.time_spp]):
            ks, cs = os.path.join(work, "%s-kiln-%d.exr" % (name, spp)), os.path.join(work, "%s-cycles-%d.exr" % (name, spp))
            kt = run_kiln(args, asset, ks, spp)
            ct = run_cycles(args, asset, cs, camera, spp, seed=0)
            results["timing"].append({"asset": name, "spp": spp, "kiln": kt, "cycles": ct})
            if name in noise_assets:
                ki, ci = rgba(ks), rgba(cs)
                m2 = covered(k, c, ki, ci)
                mean_k, mean_c = float(mean_rgb(k, m2).mean()), float(mean_rgb(c, m2).mean())
                results["noise"].append({"asset": name, "spp": spp, "ref_spp": ref_spp,
                                         "kiln_vs_kiln_ref": rmse(ki, k, m2) / mean_k,
                                         "kiln_vs_cycles_ref": rmse(ki, c, m2) / mean_c,
                                         "cycles_vs_cycles_ref": rmse(ci, c, m2) / mean_c,
                                         "kiln_ref_vs_cycles_ref": rmse(k, c, m2) / mean_c})

    text = tables(results)
    with open(os.path.join(args.out, "tables.md"), "w", encoding="utf-8") as f:
        f.write(text)
    with open(os.path.join(args.out, "results.json"), "w", encoding="utf-8") as f:
        json.dump(results, f, indent=1)
    print(text)
    log("results in", args.out)


def machine(args):
    cpu = "unknown"
    try:
        with open("/proc/cpuinfo", encoding="utf-8") as f:
            cpu = next(l.split(":", 1)[1].strip() for l in f if l.startswith("model name"))
    except (OSError, StopIteration):
        pass
    commit = subprocess.run(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"], capture_output=True, text=True).stdout.strip()
    blender = subprocess.run([args.blender, "-b", "--factory-startup", "--version"], capture_output=True,
                             text=True).stdout.splitlines()
    return {"cpu": cpu, "cores": os.cpu_count(), "threads": args.threads, "commit": commit,
            "blender": blender[0] if blender else "?", "date": time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime())}


def tables(results):
    s, m = results["settings"], results["machine"]
    out = ["kiln at %s, %s, %s (%d cores, %d threads), %s; map %s." % (
        m["commit"], m["blender"], m["cpu"], m["cores"], m["threads"], m["date"], os.path.relpath(s["environment"], ROOT)), ""]
    if results["spheres"]:
        out += ["### One sphere under the map: mean radiance, kiln / Cycles (160x120, %d spp)" % s["sphere_spp"], "",
                "| sphere | isolates | kiln / Cycles (importer's Principled) | kiln / Cycles (glTF BRDF) | RMSE / mean (glTF BRDF) |",
                "|---|---|---|---|---|"]
        for r in results["spheres"]:
            extra = ""
            if "ratio_analytic" in r:
                extra = " (kiln / analytic %.4f, Cycles Diffuse BSDF / analytic %.4f)" % (r["ratio_analytic"],
                                                                                      r["cycles_gltf_vs_analytic"])
            out.append("| %s | %s%s | %.3f | %.3f | %.3f |" % (r["sphere"], r["isolates"], extra, r["ratio_importer"],
                                                            r["ratio_gltf"], r["rmse_gltf"]))
        out.append("")
    out += ["### Shipped assets: mean radiance, kiln / Cycles (%dx%d)" % (s["width"], s["height"]), "",
            "| asset | what it shows | spp | pixels | kiln / Cycles R / G / B (importer's Principled) | luminance | "
            "kiln / Cycles R / G / B (glTF BRDF; materials rewritten) | luminance | RMSE / mean (glTF BRDF) | "
            "luminance, glTF BRDF and Cycles glossy bounces 0 |",
            "|---|---|---|---|---|---|---|---|---|---|"]
    for a in results["assets"]:
        out.append("| %s | %s | %d | %d | %s | %.3f | %s (%s) | %.3f | %.3f | %.3f |" % (
            a["asset"], a["shows"], a["spp"], a["pixels"], fmt_ratio(a["ratio_importer"]), a["ratio_luminance_importer"],
            fmt_ratio(a["ratio_gltf"]), a["rewritten"], a["ratio_luminance_gltf"], a["rmse_rel_gltf"],
            a["ratio_luminance_gltf-glossy0"]))
    if results["noise"]:
        ref = results["noise"][0]["ref_spp"]
        out += ["", "### Per-pixel RMSE against samples (relative to the reference's mean; %dx%d)" % (s["width"], s["height"]), "",
                "| asset | spp | kiln vs kiln %d spp | Cycles vs Cycles %d spp | kiln vs Cycles %d spp |" % (ref, ref, ref),
                "|---|---|---|---|---|"]
        for n in results["noise"]:
            out.append("| %s | %d | %.4f | %.4f | %.4f |" % (n["asset"], n["spp"], n["kiln_vs_kiln_ref"],
                                                          n["cycles_vs_cycles_ref"], n["kiln_vs_cycles_ref"]))
        floors = {}
        for n in results["noise"]:
            floors[n["asset"]] = n["kiln_ref_vs_cycles_ref"]
        out += ["", "kiln's %d-spp reference against Cycles' (importer's materials), the floor of the last column: %s" % (
            ref, ", ".join("%s %.4f" % kv for kv in floors.items()))]
    out += ["", "### Time at equal samples (%dx%d, %d threads; Cycles with the importer's materials)" % (
        s["width"], s["height"], s["threads"]), "",
            "| asset | spp | kiln render s (process wall) | Cycles render s (process wall) | kiln speed-up: render / wall |",
            "|---|---|---|---|---|"]
    rows = results["timing"] + [{"asset": a["asset"], "spp": a["spp"], "kiln": a["kiln_ref_time"],
                                 "cycles": a["cycles_ref_time"]} for a in results["assets"]]
    rows.sort(key=lambda r: (r["asset"], r["spp"]))
    for t in rows:
        k, c = t["kiln"], t["cycles"]
        out.append("| %s | %d | %.3f (%.2f) | %.3f (%.2f) | %.2fx / %.2fx |" % (
            t["asset"], t["spp"], k["render_s"], k["wall_s"], c["render_s"], c["wall_s"],
            c["render_s"] / k["render_s"], c["wall_s"] / k["wall_s"]))
    return "\n".join(out) + "\n"


if __name__ == "__main__":
    main()
