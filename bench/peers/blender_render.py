"""Render one glTF file with Blender Cycles, set up as close to kiln's Whitted shading as Cycles
allows, and write timings as JSON. Run by bench/peers/peer_bench.py as

  blender -b --factory-startup --python bench/peers/blender_render.py -- \
      SCENE.gltf OUT.exr STATS.json --width W --height H --spp N --threads T \
      [--glossy-bounces 8 --float]

The glTF file must hold exactly one camera and its point lights (peer_bench.py writes such a
wrapper). Cycles settings: CPU, N samples, no adaptive sampling, no denoising, diffuse bounces 0
(diffuse surfaces see only direct light, as in Whitted), up to 8 glossy and transmission bounces
(kiln's --max-depth 8), no caustics, point lights of radius 0 (hard shadows), black world,
transparent film, box pixel filter of one pixel (kiln's box 0.5 radius), smooth glass (roughness
0 on every transmissive material). Clearcoat and sheen stay as the importer sets them up (kiln
renders both lobes; the importer's sheen is Cycles' own sheen model, not glTF's Charlie lobe).
Point lights: kiln takes glTF's intensity I in candela as radiance units (irradiance I/d^2);
a Cycles point light of power P watts has intensity P/(4 pi), so P = 4 pi I.

Timings: import (glTF importer) and render (render_pre to render_post: Cycles' scene sync, BVH
build and sampling). The phases within the render come from the clock on Cycles' own status
lines, which peer_bench.py reads from Blender's output.
"""

import argparse
import json
import math
import sys
import time

import bpy
import numpy

# Blender 3.4's glTF importer calls numpy.bool, an alias NumPy 1.24 (Debian 12) removed.
if not hasattr(numpy, "bool") or "bool" in getattr(numpy, "__former_attrs__", {}):
    numpy.bool = bool

T0 = time.perf_counter()


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser(prog="blender_render.py")
    p.add_argument("scene")
    p.add_argument("output")
    p.add_argument("stats")
    p.add_argument("--width", type=int, default=640)
    p.add_argument("--height", type=int, default=480)
    p.add_argument("--spp", type=int, default=16)
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--glossy-bounces", type=int, default=8,
                   help="0: direct light alone on glossy surfaces (a highlight without its reflections)")
    p.add_argument("--float", action="store_true", help="32-bit float EXR (default half)")
    return p.parse_args(argv)


def light_intensities(path):
    """glTF point light intensities by light name (the importer's own conversion is not used)."""
    with open(path, encoding="utf-8") as f:
        g = json.load(f)
    lights = g.get("extensions", {}).get("KHR_lights_punctual", {}).get("lights", [])
    return [(l.get("name", ""), l.get("intensity", 1.0), l.get("color", [1, 1, 1])) for l in lights]


def setup_cycles(scene, args):
    scene.render.engine = "CYCLES"
    c = scene.cycles
    c.device = "CPU"
    c.samples = args.spp
    c.use_adaptive_sampling = False
    c.use_denoising = False
    c.max_bounces = 8
    c.diffuse_bounces = 0
    c.glossy_bounces = args.glossy_bounces
    c.transmission_bounces = 8
    c.transparent_max_bounces = 8
    c.volume_bounces = 0
    c.caustics_reflective = False
    c.caustics_refractive = False
    c.sample_clamp_direct = 0.0
    c.sample_clamp_indirect = 0.0
    c.pixel_filter_type = "BOX"
    c.filter_width = 1.0
    c.seed = 0
    scene.render.threads_mode = "FIXED"
    scene.render.threads = args.threads
    scene.render.resolution_x = args.width
    scene.render.resolution_y = args.height
    scene.render.resolution_percentage = 100
    scene.render.film_transparent = True
    scene.render.use_persistent_data = False
    scene.view_settings.view_transform = "Standard"
    scene.view_settings.look = "None"
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.image_settings.color_depth = "32" if args.float else "16"
    scene.render.image_settings.exr_codec = "ZIP"
    if scene.world is None:
        scene.world = bpy.data.worlds.new("black")
    scene.world.use_nodes = True
    bg = scene.world.node_tree.nodes.get("Background")
    if bg:
        bg.inputs["Strength"].default_value = 0.0


def whitted_materials():
    for mat in bpy.data.materials:
        if not mat.use_nodes:
            continue
        for node in mat.node_tree.nodes:
            if node.type != "BSDF_PRINCIPLED":
                continue
            inp = node.inputs
            if "Transmission" in inp and (inp["Transmission"].is_linked or inp["Transmission"].default_value > 0):
                inp["Roughness"].default_value = 0.0
                for link in list(inp["Roughness"].links):
                    mat.node_tree.links.remove(link)


def main():
    args = parse_args()
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    t_import = time.perf_counter()
    bpy.ops.import_scene.gltf(filepath=args.scene)
    t_import = time.perf_counter() - t_import

    with open(args.scene, encoding="utf-8") as f:
        g = json.load(f)
    cams = [o for o in scene.objects if o.type == "CAMERA"]
    if len(cams) != 1:
        raise SystemExit("blender_render.py: %s: expected exactly one camera, found %d" % (args.scene, len(cams)))
    cam = cams[0]
    scene.camera = cam
    yfov = g["cameras"][0]["perspective"]["yfov"]
    cam.data.sensor_fit = "VERTICAL"
    cam.data.angle_y = yfov
    cam.data.clip_start = g["cameras"][0]["perspective"].get("znear", 0.001)
    cam.data.clip_end = 1e6

    wanted = light_intensities(args.scene)
    lamps = [o for o in scene.objects if o.type == "LIGHT"]
    if len(lamps) != len(wanted):
        raise SystemExit("blender_render.py: %s: %d lights imported, %d in the file" % (args.scene, len(lamps), len(wanted)))
    by_name = {n: (i, c) for n, i, c in wanted}
    for lamp in lamps:
        name = lamp.data.name if lamp.data.name in by_name else lamp.name
        intensity, colour = by_name.get(name, (wanted[0][1], wanted[0][2]))
        lamp.data.energy = 4 * math.pi * intensity
        lamp.data.color = colour
        lamp.data.shadow_soft_size = 0.0
        lamp.data.use_shadow = True

    setup_cycles(scene, args)
    whitted_materials()

    times = {}

    def on_pre(*_):
        times["render_start"] = time.perf_counter()

    def on_post(*_):
        times["render_end"] = time.perf_counter()

    bpy.app.handlers.render_pre.append(on_pre)
    bpy.app.handlers.render_post.append(on_post)
    scene.render.filepath = args.output
    bpy.ops.render.render(write_still=True)

    out = {"blender": bpy.app.version_string, "import_s": t_import,
           "render_s": times["render_end"] - times["render_start"], "script_s": time.perf_counter() - T0}
    with open(args.stats, "w", encoding="utf-8") as f:
        json.dump(out, f, indent=1)


main()
