#!/usr/bin/env python3
"""Write the peer-benchmark quadric scene twice from one description: as kiln glTF
(scenes/peer_quadrics.gltf, KILN_quadric) and as POV-Ray 3.7 SDL (bench/peers/peer_quadrics.pov).

The scene: six quadric kinds (a diffuse sphere, a capped cylinder, a capped cone, a capped
paraboloid, an open hyperboloid of one sheet, a torus), a mirror sphere and a glass sphere
(ior 1.5) on a 16 x 16 checkerboard of 1 m squares, lit by two point lights, seen by one
perspective camera (640x480 aspect). Both files are generated from the same numbers, so camera,
lights, placements and materials agree by construction.

How the two models are matched (kiln: glTF metallic-roughness, Whitted; POV-Ray: Phong-style
finishes, Whitted):
  - Coordinates: glTF is right-handed +Y up, POV-Ray left-handed; every position and transform
    is written to POV-Ray with z negated (a mirror of the whole world), which shows the same image.
  - Point lights: kiln's intensity I (candela) falls off as I/d^2. POV-Ray's fade_power 2 gives
    2 / (1 + (d/fade_distance)^2); with fade_distance 1e-3 that is 2e-6/d^2 within 1e-7 at d > 1 m,
    so the POV-Ray colour is I/pi / 2e-6 (the 1/pi is the Lambert BRDF's, which POV-Ray's
    'diffuse' does not have).
  - Diffuse: POV-Ray 'diffuse 0.96' (kiln's dielectric Fresnel F0 = 0.04 takes 4% off the
    Lambert lobe at normal incidence; POV-Ray has no Fresnel on diffuse), ambient 0.
  - Highlight: kiln's GGX lobe of roughness r (alpha = r^2, F0 0.04) against POV-Ray's Blinn
    'specular k roughness rho' ((N.H)^(1/rho)): equal peak at normal incidence, k = 0.01/alpha^2,
    and equal width, 1/rho = 2/alpha^2 - 2 (the Beckmann-Phong correspondence).
  - Mirror: metallic 1, roughness 0, base 0.9 (kiln: Schlick Fresnel from F0 0.9, 0.9 at normal
    incidence rising to 1 at grazing) against POV-Ray 'reflection {0.9, 1 falloff 5}' (the same
    Schlick curve), no diffuse.
  - Glass: transmission 1, ior 1.5, KHR_materials_volume (solid: rays bend) against POV-Ray
    'rgbf 1' + 'interior { ior 1.5 }' + 'reflection { 0, 1 fresnel on } conserve_energy'. Shadow
    rays pass clear glass unattenuated in both (no caustics).
  - Depth: kiln --max-depth 8 (camera ray is depth 0, 8 bounces) = POV-Ray max_trace_level 9
    (the camera ray is level 1); kiln --min-throughput 0.001 = POV-Ray adc_bailout 0.001.
What differs: kiln widens point-light highlights on smooth surfaces to the pixel footprint
(docs/shading.md, "Highlights of point lights"), POV-Ray draws none on the mirror and glass; POV-Ray's
checker is procedural, kiln's is 256 quads of two materials (same edges); Fresnel on the
diffuse lobe is exact only at normal incidence.

Python 3 standard library only; output is deterministic.
Usage: python3 tools/make_peer_quadric_scene.py [--gltf scenes/peer_quadrics.gltf]
                                                [--pov bench/peers/peer_quadrics.pov]
"""

import argparse
import base64
import json
import math
import os
import struct

WIDTH, HEIGHT = 640, 480
YFOV_DEG = 40.0
EYE = (0.0, 5.0, 10.5)
TARGET = (0.0, 0.6, -0.8)
MAX_DEPTH = 8
MIN_THROUGHPUT = 0.001
FADE_DISTANCE = 1e-3  # POV-Ray inverse-square emulation, see the docstring

LIGHTS = [  # name, position, linear colour, intensity (candela)
    ("key", (-4.0, 7.0, 5.0), (1.0, 0.95, 0.9), 110.0),
    ("fill", (6.0, 4.5, 2.0), (0.85, 0.92, 1.0), 35.0),
]

CHECKS = 16  # squares per side, 1 m each, centred on the origin
CHECK_COLOURS = ((0.75, 0.75, 0.75), (0.08, 0.08, 0.1))
CHECK_ROUGHNESS = 0.7

# Quadrics in kiln's canonical object space (axis +Z); UPRIGHT turns object +Z to world +Y.
PRIMITIVES = [
    {"name": "sphere", "kind": "sphere", "radius": 1.0},
    {"name": "cylinder", "kind": "cylinder", "radius": 0.55, "zmin": 0.0, "zmax": 1.5, "caps": True},
    {"name": "cone", "kind": "cone", "radius": 0.7, "height": 1.7, "caps": True},
    {"name": "paraboloid", "kind": "paraboloid", "radius": 0.7, "zmin": 0.0, "zmax": 1.5, "caps": True},
    {"name": "hyperboloid", "kind": "hyperboloid_one_sheet", "radius": 0.3, "c": 0.45, "zmin": -0.75,
     "zmax": 0.75, "caps": False},
    {"name": "torus", "kind": "torus", "major_radius": 0.6, "minor_radius": 0.22},
]

# name, base colour, metallic, roughness, kind ("plastic", "mirror", "glass")
MATERIALS = [
    ("red", (0.8, 0.12, 0.1), 0.0, 0.5, "plastic"),
    ("green", (0.15, 0.6, 0.2), 0.0, 0.5, "plastic"),
    ("blue", (0.15, 0.25, 0.8), 0.0, 0.5, "plastic"),
    ("yellow", (0.85, 0.7, 0.15), 0.0, 0.5, "plastic"),
    ("orange", (0.9, 0.4, 0.1), 0.0, 0.4, "plastic"),
    ("violet", (0.5, 0.2, 0.7), 0.0, 0.5, "plastic"),
    ("mirror", (0.9, 0.9, 0.9), 1.0, 0.0, "mirror"),
    ("glass", (1.0, 1.0, 1.0), 0.0, 0.0, "glass"),
    ("check light", CHECK_COLOURS[0], 0.0, CHECK_ROUGHNESS, "plastic"),
    ("check dark", CHECK_COLOURS[1], 0.0, CHECK_ROUGHNESS, "plastic"),
]
MAT = {m[0]: i for i, m in enumerate(MATERIALS)}

UP_X = ((1, 0, 0), (0, 0, 1), (0, -1, 0))  # rotation (rows): object +Z -> world +Y, +Y -> world -Z


def rot_y(deg):
    c, s = math.cos(math.radians(deg)), math.sin(math.radians(deg))
    return ((c, 0, s), (0, 1, 0), (-s, 0, c))


def rot_x(deg):
    c, s = math.cos(math.radians(deg)), math.sin(math.radians(deg))
    return ((1, 0, 0), (0, c, -s), (0, s, c))


def matmul(a, b):
    return tuple(tuple(sum(a[i][k] * b[k][j] for k in range(3)) for j in range(3)) for i in range(3))


def scaled(m, s):
    return tuple(tuple(m[i][j] * s for j in range(3)) for i in range(3))


# name, primitive, material, translation, 3x3 linear part (world = L * object + t)
OBJECTS = [
    ("cylinder", "cylinder", "red", (-4.2, 0.0, -2.2), UP_X),
    ("cone", "cone", "green", (-2.1, 0.0, -2.6), UP_X),
    ("paraboloid", "paraboloid", "blue", (0.0, 0.0, -2.8), UP_X),
    ("hyperboloid", "hyperboloid", "yellow", (2.1, 0.75, -2.6), UP_X),
    ("torus", "torus", "orange", (4.2, 0.75, -2.2), matmul(rot_y(-25), matmul(rot_x(-60), UP_X))),
    ("diffuse sphere", "sphere", "violet", (-3.2, 0.8, 0.9), scaled(UP_X, 0.8)),
    ("mirror sphere", "sphere", "mirror", (-0.9, 1.0, 0.8), UP_X),
    ("glass sphere", "sphere", "glass", (2.2, 0.9, 1.1), scaled(UP_X, 0.9)),
]


def tidy(values):
    return [round(v, 7) + 0.0 for v in values]


def sub(a, b):
    return [a[i] - b[i] for i in range(3)]


def normalize(v):
    n = math.sqrt(sum(x * x for x in v))
    return [x / n for x in v]


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def camera_matrix():
    """glTF camera node matrix (column-major): looks along -Z at TARGET, +Y up."""
    back = normalize(sub(EYE, TARGET))
    right = normalize(cross([0, 1, 0], back))
    up = cross(back, right)
    return tidy(right + [0] + up + [0] + back + [0] + list(EYE) + [1])


def node_matrix(linear, t):
    cols = [[linear[r][c] for r in range(3)] for c in range(3)]
    return tidy(cols[0] + [0] + cols[1] + [0] + cols[2] + [0] + list(t) + [1])


def quad_buffer():
    """A unit square in the XZ plane, normal +Y: 4 positions, 4 normals, 6 uint16 indices."""
    pos = [(-0.5, 0, -0.5), (-0.5, 0, 0.5), (0.5, 0, 0.5), (0.5, 0, -0.5)]
    data = b"".join(struct.pack("<3f", *p) for p in pos)
    data += b"".join(struct.pack("<3f", 0, 1, 0) for _ in pos)
    data += struct.pack("<6H", 0, 1, 2, 0, 2, 3)
    data += b"\0" * (-len(data) % 4)
    return data


def build_gltf():
    materials = []
    for name, colour, metallic, roughness, kind in MATERIALS:
        m = {"name": name, "pbrMetallicRoughness": {"baseColorFactor": tidy(list(colour) + [1.0]),
                                                    "metallicFactor": metallic, "roughnessFactor": roughness}}
        if kind == "glass":
            m["extensions"] = {"KHR_materials_transmission": {"transmissionFactor": 1.0},
                               "KHR_materials_ior": {"ior": 1.5},
                               "KHR_materials_volume": {"thicknessFactor": 1.0}}
        materials.append(m)
    prim_index = {p["name"]: i for i, p in enumerate(PRIMITIVES)}
    nodes = []
    for name, prim, mat, t, linear in OBJECTS:
        nodes.append({"name": name, "matrix": node_matrix(linear, t),
                      "extensions": {"KILN_quadric": {"primitive": prim_index[prim], "material": MAT[mat]}}})
    for i in range(CHECKS):
        for j in range(CHECKS):
            x, z = i - CHECKS / 2 + 0.5, j - CHECKS / 2 + 0.5
            nodes.append({"mesh": (i + j) % 2, "translation": tidy([x, 0.0, z])})
    nodes.append({"name": "camera", "camera": 0, "matrix": camera_matrix()})
    for k, (name, pos, _, _) in enumerate(LIGHTS):
        nodes.append({"name": name + " light", "translation": tidy(pos),
                      "extensions": {"KHR_lights_punctual": {"light": k}}})
    data = quad_buffer()
    attrs = {"POSITION": 0, "NORMAL": 1}
    return {
        "asset": {"version": "2.0", "generator": "kiln tools/make_peer_quadric_scene.py"},
        "extensionsUsed": ["KILN_quadric", "KHR_lights_punctual", "KHR_materials_transmission",
                           "KHR_materials_ior", "KHR_materials_volume"],
        "extensions": {
            "KILN_quadric": {"primitives": PRIMITIVES},
            "KHR_lights_punctual": {"lights": [
                {"name": name, "type": "point", "color": tidy(colour), "intensity": intensity}
                for name, _, colour, intensity in LIGHTS]},
        },
        "scene": 0,
        "scenes": [{"nodes": list(range(len(nodes)))}],
        "nodes": nodes,
        "cameras": [{"name": "main", "type": "perspective",
                     "perspective": {"yfov": round(math.radians(YFOV_DEG), 7), "aspectRatio": WIDTH / HEIGHT,
                                     "znear": 0.05}}],
        "meshes": [{"name": "check light", "primitives": [{"attributes": attrs, "indices": 2,
                                                           "material": MAT["check light"]}]},
                   {"name": "check dark", "primitives": [{"attributes": attrs, "indices": 2,
                                                          "material": MAT["check dark"]}]}],
        "materials": materials,
        "buffers": [{"byteLength": len(data),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(data).decode()}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48},
                        {"buffer": 0, "byteOffset": 48, "byteLength": 48},
                        {"buffer": 0, "byteOffset": 96, "byteLength": 12}],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
             "min": [-0.5, 0, -0.5], "max": [0.5, 0, 0.5]},
            {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3"},
            {"bufferView": 2, "componentType": 5123, "count": 6, "type": "SCALAR"}],
    }


# ---- POV-Ray ----------------------------------------------------------------------------------

def f(x):
    return ("%.7g" % (x + 0.0)).replace("e+0", "e+").replace("e-0", "e-")


def vec(v):
    return "<%s>" % ", ".join(f(x) for x in v)


def flip(v):
    return (v[0], v[1], -v[2])


def pov_matrix(linear, t):
    """POV-Ray 'matrix' (row-vector convention) for world = F (L p + t), F = diag(1, 1, -1)."""
    a = [[linear[r][c] * (-1 if r == 2 else 1) for c in range(3)] for r in range(3)]
    rows = [[a[r][c] for r in range(3)] for c in range(3)]  # row c = image of object axis c
    return "matrix <%s>" % ", ".join(f(x) for x in rows[0] + rows[1] + rows[2] + list(flip(t)))


def blinn_for_ggx(roughness):
    """POV-Ray 'specular k roughness rho' with the peak and width of a GGX lobe, F0 = 0.04."""
    alpha2 = max(roughness, 0.05) ** 4
    return 0.01 / alpha2, 1.0 / max(2.0 / alpha2 - 2.0, 1.0)


def pov_finish(name):
    _, colour, _, roughness, kind = MATERIALS[MAT[name]]
    if kind == "mirror":
        return ("pigment { rgb %s } finish { ambient 0 emission 0 diffuse 0 "
                "reflection { %s, 1 falloff 5 } }" % (vec(colour), f(colour[0])))
    if kind == "glass":
        return ("pigment { rgbf <1, 1, 1, 1> } finish { ambient 0 emission 0 diffuse 0 "
                "reflection { 0, 1 fresnel on } conserve_energy } interior { ior 1.5 }")
    k, rho = blinn_for_ggx(roughness)
    return ("pigment { rgb %s } finish { ambient 0 emission 0 diffuse 0.96 specular %s roughness %s }"
            % (vec(colour), f(k), f(rho)))


def pov_shape(p):
    kind = p["kind"]
    if kind == "sphere":
        return "sphere { <0, 0, 0>, %s }" % f(p["radius"])
    if kind == "cylinder":
        return "cylinder { <0, 0, %s>, <0, 0, %s>, %s%s }" % (
            f(p["zmin"]), f(p["zmax"]), f(p["radius"]), "" if p["caps"] else " open")
    if kind == "cone":
        return "cone { <0, 0, 0>, %s, <0, 0, %s>, 0%s }" % (f(p["radius"]), f(p["height"]),
                                                            "" if p["caps"] else " open")
    if kind == "paraboloid":
        # x^2 + y^2 - (r^2 / zmax) z = 0, inside the slab zmin < z < zmax (the slab makes the caps).
        q = "quadric { <1, 1, 0>, <0, 0, 0>, <0, 0, %s>, 0 }" % f(-p["radius"] ** 2 / p["zmax"])
        slab = "plane { <0, 0, 1>, %s } plane { <0, 0, -1>, %s }" % (f(p["zmax"]), f(-p["zmin"]))
        return "intersection { %s %s }" % (q, slab) if p["caps"] else "object { %s clipped_by { %s } }" % (
            q, "intersection { %s }" % slab)
    if kind == "hyperboloid_one_sheet":
        # (x^2 + y^2)/r^2 - z^2/c^2 - 1 = 0
        r2, c2 = p["radius"] ** 2, p["c"] ** 2
        q = "quadric { <%s, %s, %s>, <0, 0, 0>, <0, 0, 0>, -1 }" % (f(1 / r2), f(1 / r2), f(-1 / c2))
        slab = "plane { <0, 0, 1>, %s } plane { <0, 0, -1>, %s }" % (f(p["zmax"]), f(-p["zmin"]))
        if p["caps"]:
            return "intersection { %s %s }" % (q, slab)
        return "object { %s clipped_by { intersection { %s } } }" % (q, slab)
    if kind == "torus":
        # POV-Ray's torus lies in its XZ plane (axis +Y); swap Y and Z for kiln's axis +Z.
        return "torus { %s, %s matrix <1, 0, 0, 0, 0, 1, 0, 1, 0, 0, 0, 0> }" % (
            f(p["major_radius"]), f(p["minor_radius"]))
    raise ValueError("no POV-Ray form for kind " + kind)


def build_pov():
    aspect = WIDTH / HEIGHT
    hfov = math.degrees(2 * math.atan(math.tan(math.radians(YFOV_DEG) / 2) * aspect))
    prims = {p["name"]: p for p in PRIMITIVES}
    out = [
        "// Generated by tools/make_peer_quadric_scene.py from the same numbers as",
        "// scenes/peer_quadrics.gltf; z is negated (POV-Ray is left-handed). Do not edit.",
        "#version 3.7;",
        "global_settings { assumed_gamma 1.0 max_trace_level %d adc_bailout %s ambient_light 0 }"
        % (MAX_DEPTH + 1, f(MIN_THROUGHPUT)),
        "background { rgb 0 }",
        "camera { perspective location %s look_at %s right x*%s up y angle %s }"
        % (vec(flip(EYE)), vec(flip(TARGET)), f(aspect), f(hfov)),
    ]
    for name, pos, colour, intensity in LIGHTS:
        scale = intensity / math.pi / (2 * FADE_DISTANCE ** 2)
        out.append("light_source { %s color rgb %s fade_distance %s fade_power 2 } // %s, %s cd"
                   % (vec(flip(pos)), vec([c * scale for c in colour]), f(FADE_DISTANCE), name, f(intensity)))
    half = CHECKS / 2
    # The checker's cubes are offset by half a square in y so that the plane y = 0 is inside one
    # layer of them (a plane on a cube boundary would flicker between colours).
    out.append("plane { y, 0 clipped_by { box { <%s, -1, %s>, <%s, 1, %s> } }" % (f(-half), f(-half), f(half), f(half)))
    out.append("  texture { pigment { checker rgb %s rgb %s translate <0, 0.5, 0> }"
               % (vec(CHECK_COLOURS[0]), vec(CHECK_COLOURS[1])))
    k, rho = blinn_for_ggx(CHECK_ROUGHNESS)
    out.append("    finish { ambient 0 emission 0 diffuse 0.96 specular %s roughness %s } } }" % (f(k), f(rho)))
    for name, prim, mat, t, linear in OBJECTS:
        out.append("object { %s // %s" % (pov_shape(prims[prim]), name))
        out.append("  %s" % pov_matrix(linear, t))
        out.append("  %s }" % pov_finish(mat))
    return "\n".join(out) + "\n"


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--gltf", default=os.path.join(here, "..", "scenes", "peer_quadrics.gltf"))
    parser.add_argument("--pov", default=os.path.join(here, "..", "bench", "peers", "peer_quadrics.pov"))
    args = parser.parse_args()
    with open(args.gltf, "w", encoding="utf-8") as out:
        json.dump(build_gltf(), out, indent=1)
        out.write("\n")
    with open(args.pov, "w", encoding="utf-8") as out:
        out.write(build_pov())
    print("wrote", os.path.normpath(args.gltf), "and", os.path.normpath(args.pov))


if __name__ == "__main__":
    main()
