"""Render one glTF file with Blender Cycles lit by an equirectangular environment map alone, set up
as close to kiln's environment lighting as Cycles allows, and write timings as JSON. Run by
bench/peers/environment_compare.py, bench/peers/peer_bench.py and tools/make_gallery.py as

  blender -b --factory-startup --python bench/peers/blender_environment.py -- \
      SCENE.gltf OUT.exr STATS.json --environment MAP.exr --camera CAMERA.json \
      [--width W --height H --spp N --threads T --seed S --glossy-bounces 8 --show-background
       --material importer|gltf]

CAMERA.json is kiln's camera, already in Blender's frame (environment_compare.py derives it from
the worldToCamera and worldToNDC attributes of kiln's EXR): {"matrix_world": 4x4 rows, "yfov":
radians}. The file's own cameras and lights are deleted: the map is the only light, as with
`kiln render --lighting studio` or `--lighting file --environment MAP.exr` on a file without lights.

The World: Environment Texture (equirectangular, linear interpolation) of MAP.exr, read as linear
radiance, looked up through a Mapping node that turns the direction by -90 degrees about Blender's
+Z. Why: Blender's glTF importer maps glTF (x, y, z) to Blender (x, -z, y); kiln puts the map's
centre (u = 0.5) along glTF -Z = Blender +Y and u = 0.75 along +X, where Cycles puts u = 0.5 along
Blender +X and u = 0.75 along -Y. Both turn clockwise seen from above as u grows and both put the
top row straight up, so a quarter turn about +Z makes them agree (environment_compare.py
--check-orientation measures it on the background and on a mirror ball).

Cycles settings: CPU, N samples, no adaptive sampling, no denoising, diffuse bounces 0 (diffuse
surfaces see the map directly and nothing else, as kiln's Whitted shading), glossy and
transmission bounces 8 (kiln's --max-depth 8; --glossy-bounces changes glossy), no caustics, no
clamping, Filter Glossy 0, box pixel filter one pixel wide (kiln's box of radius 0.5), film
transparent unless --show-background, view transform Standard (the EXR is scene-linear either way).
Materials: as the glTF importer sets them up (Principled BSDF v1), or with --material gltf
rewritten toward glTF's own BRDF, which kiln renders (see gltf_brdf below): Principled v1's
diffuse is Disney's (Burley's retro-reflection: +6.6% on a rough white sphere under the studio map)
and is not reduced by the specular layer's Fresnel, and its dielectric Fresnel is the exact curve
where glTF's is Schlick's (+6-8% on a black glossy sphere).
"""

import argparse
import json
import math
import sys
import time

import bpy
import mathutils
import numpy

# Blender 3.4's glTF importer calls numpy.bool, an alias NumPy 1.24 (Debian 12) removed.
if not hasattr(numpy, "bool") or "bool" in getattr(numpy, "__former_attrs__", {}):
    numpy.bool = bool

T0 = time.perf_counter()

# Turn of the map about Blender's +Z that puts its u = 0.5 where kiln puts it (see the docstring).
MAP_TURN_DEG = -90.0


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser(prog="blender_environment.py")
    p.add_argument("scene")
    p.add_argument("output")
    p.add_argument("stats")
    p.add_argument("--environment", required=True)
    p.add_argument("--camera", required=True, help="JSON file: matrix_world (Blender frame), yfov (radians)")
    p.add_argument("--width", type=int, default=320)
    p.add_argument("--height", type=int, default=240)
    p.add_argument("--spp", type=int, default=16)
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--glossy-bounces", type=int, default=8)
    p.add_argument("--map-turn", type=float, default=MAP_TURN_DEG, help="degrees about +Z (for the orientation check)")
    p.add_argument("--show-background", action="store_true")
    p.add_argument("--material", choices=("importer", "gltf"), default="importer",
                   help="the importer's Principled BSDF, or glTF's BRDF built from Cycles nodes")
    return p.parse_args(argv)


def setup_world(scene, path, turn_deg):
    world = bpy.data.worlds.new("environment")
    scene.world = world
    world.use_nodes = True
    nt = world.node_tree
    nt.nodes.clear()
    coord = nt.nodes.new("ShaderNodeTexCoord")
    mapping = nt.nodes.new("ShaderNodeMapping")
    mapping.vector_type = "POINT"
    mapping.inputs["Rotation"].default_value = (0.0, 0.0, math.radians(turn_deg))
    tex = nt.nodes.new("ShaderNodeTexEnvironment")
    tex.image = bpy.data.images.load(path)
    tex.image.colorspace_settings.name = "Linear"
    tex.interpolation = "Linear"
    tex.projection = "EQUIRECTANGULAR"
    bg = nt.nodes.new("ShaderNodeBackground")
    bg.inputs["Strength"].default_value = 1.0
    out = nt.nodes.new("ShaderNodeOutputWorld")
    nt.links.new(coord.outputs["Generated"], mapping.inputs["Vector"])
    nt.links.new(mapping.outputs["Vector"], tex.inputs["Vector"])
    nt.links.new(tex.outputs["Color"], bg.inputs["Color"])
    nt.links.new(bg.outputs["Background"], out.inputs["Surface"])
    world.cycles.sampling_method = "MANUAL"
    world.cycles.sample_map_resolution = max(tex.image.size[0], 256)


def gltf_dielectric_f0(scene_path):
    """{Blender material name: glTF's dielectric F0} from the file itself (Blender 3.4's importer
    folds KHR_materials_specular into Principled's Specular Tint and keeps the factor only in its
    export group): ((ior - 1) / (ior + 1))^2 x specularFactor; None where a texture or a coloured
    specularColorFactor sets it, which the rewrite leaves as imported."""
    with open(scene_path, "rb") as f:
        data = f.read()
    if data[:4] == b"glTF":
        length = int.from_bytes(data[12:16], "little")
        g = json.loads(data[20:20 + length])
    else:
        g = json.loads(data)
    out = {}
    for i, m in enumerate(g.get("materials", [])):
        ext = m.get("extensions", {})
        spec, ior = ext.get("KHR_materials_specular", {}), ext.get("KHR_materials_ior", {}).get("ior", 1.5)
        f0 = ((ior - 1.0) / (ior + 1.0)) ** 2 * spec.get("specularFactor", 1.0)
        if "specularTexture" in spec or "specularColorTexture" in spec or min(spec.get("specularColorFactor", [1, 1, 1])) < 1:
            f0 = None
        out[m.get("name", "Material_%d" % i)] = f0
    return out


def gltf_brdf(mat, f0):
    """Rewrite an imported Principled BSDF toward glTF's metallic-roughness BRDF (the specification's
    appendix B, which kiln renders): mix(dielectric, metal, metallic). The dielectric is a Lambert
    diffuse (Diffuse BSDF, roughness 0) weighted by 1 - F0 (glTF's dielectric F0, 0.04 by default),
    plus Principled's specular lobe alone (base colour black, Specular = F0 / 0.08, no tint); the
    metal is Principled at metallic 1.
    What stays Cycles' own: glTF weights the diffuse by 1 - Schlick's Fresnel at V.H (the constant
    is its value for the directions of a Lambert lobe near normal incidence), Principled's dielectric
    Fresnel is the exact curve for the ior Specular implies (6-8% more than Schlick's on a glossy
    black sphere), and Cycles 3.4's GGX shadowing is separable Smith, where glTF's is height-correlated
    (Cycles 7% darker on a metal sphere of roughness 1, equal up to 0.5). Emission is added and alpha
    mixed with Transparent as the importer does; its textures, Separate Color and Normal Map nodes
    are kept and rewired. Materials with transmission, clearcoat, sheen or subsurface are left as
    imported. Returns whether it rewrote."""
    nt = mat.node_tree
    p = next((n for n in nt.nodes if n.type == "BSDF_PRINCIPLED"), None)
    out = next((n for n in nt.nodes if n.type == "OUTPUT_MATERIAL" and n.is_active_output), None)
    if f0 is None or p is None or out is None or not out.inputs["Surface"].is_linked or out.inputs["Surface"].links[0].from_node != p:
        return False  # the importer added lobes of its own (sheen: a Velvet BSDF added to Principled)
    for name in ("Transmission", "Clearcoat", "Sheen", "Subsurface"):
        if p.inputs[name].is_linked or p.inputs[name].default_value > 0.0:
            return False

    def copy(name, dst):
        src = p.inputs[name]
        if src.is_linked:
            nt.links.new(src.links[0].from_socket, dst)
        else:
            dst.default_value = src.default_value

    def node(kind, **inputs):
        n = nt.nodes.new(kind)
        for key, value in inputs.items():
            n.inputs[key].default_value = value
        return n

    diffuse = node("ShaderNodeBsdfDiffuse", Roughness=0.0)  # Lambert
    copy("Base Color", diffuse.inputs["Color"])
    copy("Normal", diffuse.inputs["Normal"])
    weighted_diffuse = node("ShaderNodeMixShader", Fac=f0)  # (1 - F0) x diffuse: shader 2 is nothing
    nt.links.new(diffuse.outputs["BSDF"], weighted_diffuse.inputs[1])
    specular = node("ShaderNodeBsdfPrincipled", Metallic=0.0, Specular=f0 / 0.08, **{
        "Base Color": (0.0, 0.0, 0.0, 1.0), "Specular Tint": 0.0})
    for name in ("Roughness", "Normal"):
        copy(name, specular.inputs[name])
    dielectric = node("ShaderNodeAddShader")
    nt.links.new(weighted_diffuse.outputs["Shader"], dielectric.inputs[0])
    nt.links.new(specular.outputs["BSDF"], dielectric.inputs[1])

    metal = node("ShaderNodeBsdfPrincipled", Metallic=1.0)
    for name in ("Base Color", "Roughness", "Normal"):
        copy(name, metal.inputs[name])
    surface = node("ShaderNodeMixShader")
    copy("Metallic", surface.inputs["Fac"])
    nt.links.new(dielectric.outputs["Shader"], surface.inputs[1])
    nt.links.new(metal.outputs["BSDF"], surface.inputs[2])
    result = surface.outputs["Shader"]

    emission = p.inputs["Emission"]
    if emission.is_linked or any(c > 0.0 for c in emission.default_value[:3]):
        em = node("ShaderNodeEmission")
        copy("Emission", em.inputs["Color"])
        copy("Emission Strength", em.inputs["Strength"])
        add = node("ShaderNodeAddShader")
        nt.links.new(result, add.inputs[0])
        nt.links.new(em.outputs["Emission"], add.inputs[1])
        result = add.outputs["Shader"]
    alpha = p.inputs["Alpha"]
    if alpha.is_linked or alpha.default_value < 1.0:
        mix = node("ShaderNodeMixShader")
        copy("Alpha", mix.inputs["Fac"])
        nt.links.new(node("ShaderNodeBsdfTransparent").outputs["BSDF"], mix.inputs[1])
        nt.links.new(result, mix.inputs[2])
        result = mix.outputs["Shader"]
    nt.links.new(result, out.inputs["Surface"])
    return True


def gltf_default_material(scene):
    """glTF's default material (white, metallic 1, roughness 1) on meshes the importer left without
    one (it leaves primitives without a material to Blender's default grey diffuse)."""
    default = None
    for obj in scene.objects:
        if obj.type == "MESH" and not any(slot.material for slot in obj.material_slots):
            if default is None:
                default = bpy.data.materials.new("glTF default")
                default.use_nodes = True
                p = default.node_tree.nodes["Principled BSDF"]
                p.inputs["Base Color"].default_value = (1.0, 1.0, 1.0, 1.0)
                p.inputs["Metallic"].default_value = 1.0
                p.inputs["Roughness"].default_value = 1.0
            obj.data.materials.clear()
            obj.data.materials.append(default)


def setup_cycles(scene, args):
    scene.render.engine = "CYCLES"
    c = scene.cycles
    c.device = "CPU"
    c.samples = args.spp
    c.use_adaptive_sampling = False
    c.use_denoising = False
    c.max_bounces = max(8, args.glossy_bounces)
    c.diffuse_bounces = 0
    c.glossy_bounces = args.glossy_bounces
    c.transmission_bounces = 8
    c.transparent_max_bounces = 8
    c.volume_bounces = 0
    c.caustics_reflective = False
    c.caustics_refractive = False
    c.blur_glossy = 0.0
    c.sample_clamp_direct = 0.0
    c.sample_clamp_indirect = 0.0
    c.pixel_filter_type = "BOX"
    c.filter_width = 1.0
    c.seed = args.seed
    scene.render.threads_mode = "FIXED"
    scene.render.threads = args.threads
    scene.render.resolution_x = args.width
    scene.render.resolution_y = args.height
    scene.render.resolution_percentage = 100
    scene.render.film_transparent = not args.show_background
    scene.render.use_persistent_data = False
    scene.view_settings.view_transform = "Standard"
    scene.view_settings.look = "None"
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.image_settings.color_depth = "32"
    scene.render.image_settings.exr_codec = "ZIP"


def setup_camera(scene, path):
    with open(path, encoding="utf-8") as f:
        cam_spec = json.load(f)
    data = bpy.data.cameras.new("kiln camera")
    data.sensor_fit = "VERTICAL"
    data.angle_y = cam_spec["yfov"]
    data.clip_start = cam_spec.get("clip_start", 1e-4)
    data.clip_end = 1e6
    cam = bpy.data.objects.new("kiln camera", data)
    scene.collection.objects.link(cam)
    cam.matrix_world = mathutils.Matrix(cam_spec["matrix_world"])
    scene.camera = cam


def main():
    args = parse_args()
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    t_import = time.perf_counter()
    bpy.ops.import_scene.gltf(filepath=args.scene)
    t_import = time.perf_counter() - t_import
    for obj in [o for o in scene.objects if o.type in ("CAMERA", "LIGHT")]:
        bpy.data.objects.remove(obj, do_unlink=True)
    rewritten = []
    if args.material == "gltf":
        f0 = gltf_dielectric_f0(args.scene)
        rewritten = [m.name for m in bpy.data.materials if m.use_nodes and gltf_brdf(m, f0.get(m.name, 0.04))]
        gltf_default_material(scene)
    setup_camera(scene, args.camera)
    setup_world(scene, args.environment, args.map_turn)
    setup_cycles(scene, args)

    times = {}
    bpy.app.handlers.render_pre.append(lambda *_: times.__setitem__("start", time.perf_counter()))
    bpy.app.handlers.render_post.append(lambda *_: times.__setitem__("end", time.perf_counter()))
    scene.render.filepath = args.output
    bpy.ops.render.render(write_still=True)
    out = {"blender": bpy.app.version_string, "import_s": t_import, "render_s": times["end"] - times["start"],
           "script_s": time.perf_counter() - T0,
           "materials": len([m for m in bpy.data.materials if m.users]), "rewritten": rewritten}
    with open(args.stats, "w", encoding="utf-8") as f:
        json.dump(out, f, indent=1)


main()
