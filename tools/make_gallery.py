#!/usr/bin/python3
"""Render the README's gallery: shipped glTF assets (../shared/assets) by kiln under its default
lighting (no lights in the file, no --environment: kiln's studio environment,
share/environments/studio.exr) beside the same assets in Blender Cycles with the same EXR as its
World, and write docs/gallery/*.png and the Markdown of docs/gallery.md.

kiln:   kiln render ASSET -o OUT.exr --width 320 --height 240 --spp 64 --show-background
        (the asset's first camera, else kiln's default camera; the studio map seen behind it)
Cycles: bench/peers/blender_environment.py through kiln's camera (read from the worldToCamera and
        worldToNDC attributes of kiln's EXR), the same map turned to kiln's orientation, the glTF
        importer's materials as they come (Principled BSDF v1), diffuse bounces 0, glossy and
        transmission bounces 8, box filter one pixel wide, 64 samples, background shown.

Each picture is kiln (left) and Cycles (right), 320x240 each, linear radiance clipped at 1 and
encoded sRGB (no tone mapping: the view transform Standard of both). Writes
docs/gallery/NAME.png (the pair) and prints the Markdown it puts into docs/gallery.md between
the markers `<!-- gallery:begin -->` and `<!-- gallery:end -->` (the file is created if missing).

Usage: /usr/bin/python3 tools/make_gallery.py [--kiln build/renderer/app/kiln] [--assets ../shared/assets]
           [--out docs/gallery] [--spp 64] [--threads 2] [--only NAME,...]
Needs: Blender 3.4 with Cycles (Debian 12's `blender`), python3-numpy, python3-openimageio. About
2 minutes on 2 cores.
"""

import argparse
import os
import shutil
import subprocess
import sys
import time

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
sys.path.insert(0, os.path.join(ROOT, "bench", "peers"))
import environment_compare as ec  # noqa: E402  (read_exr, blender_camera, run_cycles, to_png)
import numpy as np  # noqa: E402

# name: (path under the assets folder, caption)
GALLERY = [
    ("DamagedHelmet", "DamagedHelmet/glTF-Binary/DamagedHelmet.glb", "textured metal and dielectric, emissive"),
    ("ToyCar", "ToyCar/glTF/ToyCar.gltf", "clearcoat, sheen, glass; the asset's own camera"),
    ("MetalRoughSpheresNoTextures", "MetalRoughSpheresNoTextures/glTF-Binary/MetalRoughSpheresNoTextures.glb",
     "metal (top) and dielectric spheres, smooth (left) to rough (right)"),
    ("GlassVaseFlowers", "GlassVaseFlowers/glTF-Binary/GlassVaseFlowers.glb",
     "a glass vase (transmission, volume; right) and an alpha-blended one (left), alpha-masked flowers"),
    ("SheenCloth", "SheenCloth/glTF/SheenCloth.gltf", "KHR_materials_sheen"),
    ("ClearCoatCarPaint", "ClearCoatCarPaint/glTF-Binary/ClearCoatCarPaint.glb", "KHR_materials_clearcoat"),
]
BEGIN, END = "<!-- gallery:begin -->", "<!-- gallery:end -->"


def log(*parts):
    print("make_gallery:", *parts, file=sys.stderr, flush=True)


def render_kiln(args, asset, exr):
    cmd = [args.kiln, "render", asset, "-o", exr, "--width", str(args.width), "--height", str(args.height),
           "--spp", str(args.spp), "--threads", str(args.threads), "--float", "--aovs", "beauty", "--show-background"]
    t0 = time.perf_counter()
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, errors="replace")
    if p.returncode != 0:
        raise RuntimeError("kiln failed on %s: %s" % (asset, p.stdout[-1000:]))
    return time.perf_counter() - t0


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--kiln", default=os.path.join(ROOT, "build", "renderer", "app", "kiln"))
    ap.add_argument("--blender", default=shutil.which("blender") or "blender")
    ap.add_argument("--assets", default=os.path.normpath(os.path.join(ROOT, "..", "shared", "assets")))
    ap.add_argument("--out", default=os.path.join(ROOT, "docs", "gallery"))
    ap.add_argument("--markdown", default=os.path.join(ROOT, "docs", "gallery.md"))
    ap.add_argument("--work", default=os.path.join(ROOT, "build", "gallery"))
    ap.add_argument("--spp", type=int, default=64)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--only", default="", help="comma-separated names of GALLERY")
    args = ap.parse_args()
    args.width, args.height, args.environment = 320, 240, ec.STUDIO
    if not os.access(args.kiln, os.X_OK):
        sys.exit("make_gallery.py: %s: no kiln executable" % args.kiln)
    if not shutil.which(args.blender):
        sys.exit("make_gallery.py: %s: Blender is not installed (apt-get install blender)" % args.blender)
    os.makedirs(args.out, exist_ok=True)
    os.makedirs(args.work, exist_ok=True)
    only = set(filter(None, args.only.split(",")))
    lines = ["| kiln (studio default) | Cycles (same map as World) |", "|---|---|"]
    rows = []
    for name, rel, caption in GALLERY:
        if only and name not in only:
            continue
        asset = os.path.join(args.assets, rel)
        if not os.path.isfile(asset):
            log("skipping %s: %s not found" % (name, asset))
            continue
        k_exr, c_exr = os.path.join(args.work, name + "-kiln.exr"), os.path.join(args.work, name + "-cycles.exr")
        k_wall = render_kiln(args, asset, k_exr)
        k, _, attrs = ec.read_exr(k_exr)
        camera = ec.blender_camera(attrs, args.width, args.height)
        c_time = ec.run_cycles(args, asset, c_exr, camera, args.spp, extra=["--show-background"])
        c = ec.rgba(c_exr)
        pair = np.concatenate([k[:, :, :3], c[:, :, :3]], axis=1)
        png = os.path.join(args.out, name + ".png")
        ec.to_png(pair, png)
        rows.append((name, caption, os.path.relpath(png, os.path.dirname(os.path.abspath(args.markdown)))))
        log("%s: kiln %.1f s, Cycles %.1f s (process wall) -> %s" % (name, k_wall, c_time["wall_s"], png))
    snippet = ["%s" % BEGIN, ""]
    for name, caption, rel in rows:
        snippet += ["**%s**: %s" % (name, caption), "", "![%s: kiln (left), Cycles (right)](%s)" % (name, rel), ""]
    snippet.append(END)
    text = "\n".join(snippet)
    print(text)
    if not only:
        write_markdown(args.markdown, text)


def write_markdown(path, snippet):
    """Replace the generated block of docs/gallery.md (or write a minimal page)."""
    if os.path.isfile(path):
        with open(path, encoding="utf-8") as f:
            page = f.read()
        if BEGIN in page and END in page:
            page = page[:page.index(BEGIN)] + snippet + page[page.index(END) + len(END):]
        else:
            page = page.rstrip("\n") + "\n\n" + snippet + "\n"
    else:
        page = "# Gallery\n\nkiln (left) and Cycles (right); `tools/make_gallery.py` writes this block.\n\n" + snippet + "\n"
    with open(path, "w", encoding="utf-8") as f:
        f.write(page)
    log("wrote", path)


if __name__ == "__main__":
    main()
