#!/usr/bin/env python3
"""Generate kiln's demo scene: scenes/cornell_box.gltf, scenes/cornell_box.bin, scenes/checker.png.

A closed Cornell-box-like room (metres, +Y up) that shows what Whitted shading does exactly:
a mirror, glass with exact Fresnel and refraction, analytic quadrics (KILN_quadric), a texture
and hard shadows from two point lights.

  room        x in [-1, 1], y in [0, 2], z from the back wall (-1) to a front wall (4) behind the
              camera "main" at (0, 0.92, 2.9), which looks 7 degrees down: the room is closed so
              that the mirror and the glass reflect walls, never the black outside
  walls       white back and front walls and ceiling, red left wall (x = -1), green right wall
  floor       checkerboard baseColorTexture (checker.png, bilinear, KHR_texture_transform
              repeats it: 12.5 cm checks, 8 texels each, never minified enough to need mip-maps)
  ceiling     one mesh with a 0.5 m square opening over the key light: the emissive panel sits
              1 cm above the ceiling plane and the point light 1 cm below it, so nothing stands
              between the light and the room (a panel below the ceiling shadowed a band of it)
  mirror      a thin mirror slab (metallic 1, roughness 0) on the back wall's left half
  glass       a capped glass cylinder (transmission 1, ior 1.5, volume with a faint blue-green
              absorption) at the front left: the checker floor and the ring seen through it
  quadrics    a blue sphere, a yellow torus lying on the floor (in front of the mirror, so it is
              seen in it too) and an orange capped cone; every object stands 1 mm into the floor
              (a base exactly on it would be a coincident surface)
  lights      the key light at the ceiling opening and a weaker fill light near the camera

No curved surface is a perfect mirror or perfect glass in view of a point light's reflection:
the mirror is flat and the glass is a vertical cylinder (its side's normals are horizontal while
the camera and both lights are above every point of it), and the lights' mirror images in every
flat face fall outside that face as the camera sees it; so the picture shows no point-light highlight of a delta surface, which a renderer
can only draw as a one-pixel spike or not at all.

Geometry is three small meshes stored once: a unit quad (the walls, the floor and the light panel),
the ceiling with its opening, and a unit cube with flat per-face normals (the mirror slab).
Materials are per primitive in glTF, so each material gets its own mesh whose primitive points
at the shared accessors; the white wall mesh is placed by two nodes. Transforms use TRS and
matrix forms under parent nodes whose own transforms matter.

Python 3 standard library only. Output is deterministic: running the script twice gives
identical bytes. After writing, the files are read back and validated (use --no-validate to skip).

Usage: python3 tools/make_demo_scene.py [--out-dir DIR] [--no-validate]
"""

import argparse
import json
import math
import os
import struct
import sys
import zlib

GENERATOR = "kiln tools/make_demo_scene.py"
GLTF_NAME = "cornell_box.gltf"
BIN_NAME = "cornell_box.bin"
PNG_NAME = "checker.png"

ARRAY_BUFFER = 34962
ELEMENT_ARRAY_BUFFER = 34963
FLOAT = 5126
UNSIGNED_SHORT = 5123
LINEAR = 9729
REPEAT = 10497

COMPONENT_SIZE = {5120: 1, 5121: 1, 5122: 2, 5123: 2, 5125: 4, 5126: 4}
COMPONENT_FORMAT = {5120: "b", 5121: "B", 5122: "h", 5123: "H", 5125: "I", 5126: "f"}
TYPE_COUNT = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4, "MAT4": 16}


# --------------------------------------------------------------------------------------------
# Small vector / matrix helpers (matrices are row-major lists of 4 rows here; glTF stores
# column-major, see to_gltf_matrix).

def sub(a, b):
    return [a[i] - b[i] for i in range(3)]


def add(a, b):
    return [a[i] + b[i] for i in range(3)]


def scale(a, s):
    return [x * s for x in a]


def dot(a, b):
    return sum(a[i] * b[i] for i in range(3))


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def length(a):
    return math.sqrt(dot(a, a))


def normalize(a):
    n = length(a)
    return [x / n for x in a]


def mat_mul(a, b):
    return [[sum(a[r][k] * b[k][c] for k in range(4)) for c in range(4)] for r in range(4)]


def identity():
    return [[1.0 if r == c else 0.0 for c in range(4)] for r in range(4)]


def mat_translate(t):
    m = identity()
    for i in range(3):
        m[i][3] = t[i]
    return m


def mat_scale(s):
    m = identity()
    for i in range(3):
        m[i][i] = s[i]
    return m


def mat_rotate_quat(q):
    x, y, z, w = q
    return [
        [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w), 0.0],
        [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w), 0.0],
        [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y), 0.0],
        [0.0, 0.0, 0.0, 1.0],
    ]


def quat_axis_angle(axis, degrees):
    """glTF quaternion [x, y, z, w] for a right-handed rotation about a unit axis."""
    half = math.radians(degrees) / 2.0
    s = math.sin(half)
    return [axis[0] * s, axis[1] * s, axis[2] * s, math.cos(half)]


def trs_matrix(node):
    t = node.get("translation", [0.0, 0.0, 0.0])
    r = node.get("rotation", [0.0, 0.0, 0.0, 1.0])
    s = node.get("scale", [1.0, 1.0, 1.0])
    return mat_mul(mat_translate(t), mat_mul(mat_rotate_quat(r), mat_scale(s)))


def node_local_matrix(node):
    if "matrix" in node:
        m = node["matrix"]  # column-major
        return [[m[c * 4 + r] for c in range(4)] for r in range(4)]
    return trs_matrix(node)


def to_gltf_matrix(m):
    """Row-major 4x4 to glTF's column-major 16 floats (rounded for a tidy, stable file)."""
    return [tidy(m[r][c]) for c in range(4) for r in range(4)]


def transform_point(m, p):
    return [sum(m[r][k] * p[k] for k in range(3)) + m[r][3] for r in range(3)]


def transform_dir(m, d):
    return [sum(m[r][k] * d[k] for k in range(3)) for r in range(3)]


def tidy(x, digits=7):
    """Round for the JSON (avoids 0.30000000000000004 and -0.0)."""
    v = round(float(x), digits)
    return 0.0 if v == 0.0 else v


def tidy_list(values, digits=7):
    return [tidy(v, digits) for v in values]


# --------------------------------------------------------------------------------------------
# Checkerboard PNG (8-bit RGB, no filtering, zlib level 9: deterministic).

CHECKER_SIZE = 64
CHECKER_CELLS = 8
CHECKER_COLOR_A = (214, 208, 196)  # sRGB warm light grey
CHECKER_COLOR_B = (62, 68, 84)     # sRGB dark slate


def png_chunk(kind, data):
    return (struct.pack(">I", len(data)) + kind + data
            + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF))


def make_checker_png():
    size, cell = CHECKER_SIZE, CHECKER_SIZE // CHECKER_CELLS
    raw = bytearray()
    for y in range(size):
        raw.append(0)  # filter type None
        for x in range(size):
            colour = CHECKER_COLOR_A if ((x // cell) + (y // cell)) % 2 == 0 else CHECKER_COLOR_B
            raw.extend(colour)
    ihdr = struct.pack(">IIBBBBB", size, size, 8, 2, 0, 0, 0)  # 8-bit, colour type 2 (RGB)
    return (b"\x89PNG\r\n\x1a\n" + png_chunk(b"IHDR", ihdr)
            + png_chunk(b"IDAT", zlib.compress(bytes(raw), 9)) + png_chunk(b"IEND", b""))


# --------------------------------------------------------------------------------------------
# Geometry

def face_vertices(center, u, v, half_u, half_v):
    """Four corners of a rectangle, counter-clockwise seen from the side u x v points to.

    UVs follow glTF (origin at the top-left of the image), so the texture appears upright with
    +v as "up" on the face.
    """
    n = normalize(cross(u, v))
    corners = [(-1, -1, (0.0, 1.0)), (1, -1, (1.0, 1.0)), (1, 1, (1.0, 0.0)), (-1, 1, (0.0, 0.0))]
    verts = []
    for su, sv, uv in corners:
        p = add(center, add(scale(u, su * half_u), scale(v, sv * half_v)))
        verts.append((p, n, uv))
    return verts


def make_quad():
    """Unit quad in the XY plane, centred at the origin, front face (normal) towards +Z."""
    verts = face_vertices([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], 0.5, 0.5)
    return verts, [0, 1, 2, 0, 2, 3]


def make_cube():
    """Unit cube [-0.5, 0.5]^3 with flat per-face normals pointing outwards: 24 vertices."""
    faces = [  # (normal, u, v) with u x v = normal
        ([1, 0, 0], [0, 0, -1], [0, 1, 0]),
        ([-1, 0, 0], [0, 0, 1], [0, 1, 0]),
        ([0, 1, 0], [1, 0, 0], [0, 0, -1]),
        ([0, -1, 0], [1, 0, 0], [0, 0, 1]),
        ([0, 0, 1], [1, 0, 0], [0, 1, 0]),
        ([0, 0, -1], [-1, 0, 0], [0, 1, 0]),
    ]
    verts, indices = [], []
    for n, u, v in faces:
        n, u, v = [list(map(float, a)) for a in (n, u, v)]
        assert cross(u, v) == n, (n, u, v)
        base = len(verts)
        verts.extend(face_vertices(scale(n, 0.5), u, v, 0.5, 0.5))
        indices.extend([base, base + 1, base + 2, base, base + 2, base + 3])
    return verts, indices


class BufferBuilder:
    """Accumulates the binary buffer, its bufferViews and accessors (each view 4-byte aligned)."""

    def __init__(self):
        self.data = bytearray()
        self.buffer_views = []
        self.accessors = []

    def _view(self, payload, target, name):
        while len(self.data) % 4:
            self.data.append(0)
        view = {"buffer": 0, "byteOffset": len(self.data), "byteLength": len(payload),
                "target": target, "name": name}
        self.data.extend(payload)
        self.buffer_views.append(view)
        return len(self.buffer_views) - 1

    def add_floats(self, rows, acc_type, name, with_bounds=False):
        flat = [c for row in rows for c in row]
        payload = struct.pack("<%df" % len(flat), *flat)
        view = self._view(payload, ARRAY_BUFFER, name)
        acc = {"bufferView": view, "byteOffset": 0, "componentType": FLOAT,
               "count": len(rows), "type": acc_type, "name": name}
        if with_bounds:
            # Bounds of the float32 values actually stored.
            stored = [struct.unpack("<f", struct.pack("<f", c))[0] for c in flat]
            n = TYPE_COUNT[acc_type]
            acc["min"] = [min(stored[i::n]) for i in range(n)]
            acc["max"] = [max(stored[i::n]) for i in range(n)]
        self.accessors.append(acc)
        return len(self.accessors) - 1

    def add_indices(self, indices, name):
        payload = struct.pack("<%dH" % len(indices), *indices)
        view = self._view(payload, ELEMENT_ARRAY_BUFFER, name)
        self.accessors.append({"bufferView": view, "byteOffset": 0,
                               "componentType": UNSIGNED_SHORT, "count": len(indices),
                               "type": "SCALAR", "name": name})
        return len(self.accessors) - 1

    def add_mesh_data(self, verts, indices, prefix):
        attrs = {
            "POSITION": self.add_floats([v[0] for v in verts], "VEC3", prefix + "_positions", True),
            "NORMAL": self.add_floats([v[1] for v in verts], "VEC3", prefix + "_normals"),
            "TEXCOORD_0": self.add_floats([v[2] for v in verts], "VEC2", prefix + "_texcoords"),
        }
        return attrs, self.add_indices(indices, prefix + "_indices")


# --------------------------------------------------------------------------------------------
# The scene

def material(name, base, metallic, roughness, **extra):
    pbr = {"baseColorFactor": tidy_list(list(base) + [1.0], 4),
           "metallicFactor": metallic, "roughnessFactor": roughness}
    m = {"name": name, "pbrMetallicRoughness": pbr}
    if "texture" in extra:
        info = {"index": extra["texture"], "texCoord": 0}
        if "uv_scale" in extra:
            info["extensions"] = {"KHR_texture_transform": {"scale": tidy_list(extra["uv_scale"], 6)}}
        pbr["baseColorTexture"] = info
    if "emissive" in extra:
        m["emissiveFactor"] = tidy_list(extra["emissive"], 4)
    extensions = {}
    if "emissive_strength" in extra:
        extensions["KHR_materials_emissive_strength"] = {"emissiveStrength": extra["emissive_strength"]}
    if "glass" in extra:
        attenuation, distance = extra["glass"]
        extensions["KHR_materials_transmission"] = {"transmissionFactor": 1.0}
        extensions["KHR_materials_ior"] = {"ior": 1.5}
        extensions["KHR_materials_volume"] = {"thicknessFactor": 0.3,
                                              "attenuationColor": tidy_list(attenuation, 4),
                                              "attenuationDistance": distance}
    if extensions:
        m["extensions"] = extensions
    return m


def make_frame(outer_min, outer_max, hole_min, hole_max):
    """A rectangle with a rectangular hole in the XY plane, normal +Z: 8 vertices, 8 triangles.

    One mesh with shared vertices, so the ring is watertight (separate quads around the hole
    would meet in T-junctions that rounding can open into pin-holes).
    """
    (x0, y0), (x1, y1) = outer_min, outer_max
    (h0, k0), (h1, k1) = hole_min, hole_max
    corners = [(x0, y0), (x1, y0), (x1, y1), (x0, y1), (h0, k0), (h1, k0), (h1, k1), (h0, k1)]
    verts = [([x, y, 0.0], [0.0, 0.0, 1.0], ((x - x0) / (x1 - x0), (y1 - y) / (y1 - y0)))
             for x, y in corners]
    indices = []
    for side in range(4):  # outer edge o0-o1 and the inner edge below it, counter-clockwise
        o0, o1, i0, i1 = side, (side + 1) % 4, 4 + side, 4 + (side + 1) % 4
        indices.extend([o0, o1, i1, o0, i1, i0])
    return verts, indices


# Room (metres, +Y up): x in [-1, 1], y in [0, 2], z from the back wall at -1 to a front wall at
# ROOM_FRONT behind the camera. The room is closed so that the mirror and the glass show walls,
# not the black outside, in every direction.
ROOM_FRONT = 4.0
CEILING_HOLE = 0.25      # half size of the opening over the ceiling light
PANEL_HEIGHT = 2.01      # the emissive panel, above the ceiling plane and the key light
KEY_LIGHT = [0.0, 1.99, 0.0]
FILL_LIGHT = [0.3, 1.7, 2.6]
CAMERA = [0.0, 0.92, 2.9]
CAMERA_PITCH = -7.0      # degrees about X: looks slightly down at the objects
# The mirror: a 2 cm slab on the back wall's left half, 1 mm in front of it. The fill light casts its
# shadow on the wall as a strip about a pixel wide beside the left edge; a thinner slab makes that
# strip a fraction of a pixel, which 4 samples a pixel draw as a dotted line.
MIRROR_MIN = [-0.86, 0.06, -0.999]
MIRROR_MAX = [-0.14, 1.56, -0.979]
# Objects stand 1 mm into the floor: a base exactly on it would be a coincident surface.
SINK = 0.001

UPRIGHT = [-math.sqrt(0.5), 0.0, 0.0, math.sqrt(0.5)]  # -90 degrees about X: object +Z to world +Y

QUADRICS = [  # KILN_quadric definitions (docs/quadrics.md), axis along object +Z
    {"name": "glass_column", "kind": "cylinder", "radius": 0.19, "zmin": 0.0, "zmax": 0.58, "caps": True},
    {"name": "ball", "kind": "sphere", "radius": 0.24},
    {"name": "ring", "kind": "torus", "major_radius": 0.19, "minor_radius": 0.065},
    {"name": "cone", "kind": "cone", "radius": 0.2, "height": 0.55, "caps": True},
]


def quadric_bounds(definition, node):
    """World bounds of an upright quadric node (rotation UPRIGHT or none, no scale)."""
    t = node["translation"]
    kind = definition["kind"]
    if kind == "sphere":
        r = definition["radius"]
        return [t[0] - r, t[1] - r, t[2] - r], [t[0] + r, t[1] + r, t[2] + r]
    if kind == "cylinder":
        r = definition["radius"]
        return ([t[0] - r, t[1] + definition["zmin"], t[2] - r],
                [t[0] + r, t[1] + definition["zmax"], t[2] + r])
    if kind == "cone":
        r = definition["radius"]
        return [t[0] - r, t[1], t[2] - r], [t[0] + r, t[1] + definition["height"], t[2] + r]
    if kind == "torus":
        r, m = definition["major_radius"] + definition["minor_radius"], definition["minor_radius"]
        return [t[0] - r, t[1] - m, t[2] - r], [t[0] + r, t[1] + m, t[2] + r]
    raise ValueError(kind)


def build_scene():
    buf = BufferBuilder()
    quad_verts, quad_indices = make_quad()
    frame_verts, frame_indices = make_frame((-1.0, -1.0), (1.0, ROOM_FRONT),
                                            (-CEILING_HOLE, -CEILING_HOLE), (CEILING_HOLE, CEILING_HOLE))
    cube_verts, cube_indices = make_cube()
    quad_attrs, quad_idx = buf.add_mesh_data(quad_verts, quad_indices, "quad")
    cube_attrs, cube_idx = buf.add_mesh_data(cube_verts, cube_indices, "cube")
    frame_attrs, frame_idx = buf.add_mesh_data(frame_verts, frame_indices, "ceiling")

    depth = ROOM_FRONT + 1.0  # the room's length along z
    materials = [
        material("white", (0.725, 0.71, 0.68), 0.0, 1.0),                     # 0
        material("red", (0.63, 0.065, 0.05), 0.0, 1.0),                       # 1
        material("green", (0.14, 0.45, 0.091), 0.0, 1.0),                     # 2
        material("mirror", (0.95, 0.95, 0.95), 1.0, 0.0),                     # 3
        # 8 x 8 checks an image: 2 images across, 5 along, so every check is 12.5 cm square.
        material("checker_floor", (1.0, 1.0, 1.0), 0.0, 0.9, texture=0,      # 4
                 uv_scale=(2.0, depth)),
        material("light_panel", (0.0, 0.0, 0.0), 0.0, 1.0,                    # 5
                 emissive=(1.0, 0.95, 0.88), emissive_strength=4.0),
        material("glass", (1.0, 1.0, 1.0), 0.0, 0.0,                          # 6
                 glass=((0.85, 0.96, 1.0), 0.6)),
        material("blue", (0.13, 0.26, 0.62), 0.0, 0.5),                       # 7
        material("yellow", (0.85, 0.58, 0.1), 0.0, 0.45),                     # 8
        material("orange", (0.8, 0.3, 0.08), 0.0, 0.5),                       # 9
    ]

    def mesh(name, attrs, idx, mat):
        return {"name": name, "primitives": [
            {"attributes": dict(attrs), "indices": idx, "material": mat, "mode": 4}]}

    meshes = [
        mesh("wall_white", quad_attrs, quad_idx, 0),      # 0: back and front walls
        mesh("wall_red", quad_attrs, quad_idx, 1),        # 1
        mesh("wall_green", quad_attrs, quad_idx, 2),      # 2
        mesh("light_panel", quad_attrs, quad_idx, 5),     # 3
        mesh("floor_checker", quad_attrs, quad_idx, 4),   # 4
        mesh("ceiling", frame_attrs, frame_idx, 0),       # 5
        mesh("cube_mirror", cube_attrs, cube_idx, 3),     # 6
    ]

    x_axis, y_axis = [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]

    def q(axis, deg):
        return tidy_list(quat_axis_angle(axis, deg), 9)

    mid_z = (ROOM_FRONT - 1.0) / 2.0
    # The red wall as a matrix (turn +90 degrees about Y, then scale the quad to depth x 2).
    left_wall_matrix = mat_mul(mat_translate([-1.0, 1.0, mid_z]),
                               mat_mul(mat_rotate_quat(quat_axis_angle(y_axis, 90.0)),
                                       mat_scale([depth, 2.0, 1.0])))

    def quadric(name, primitive, mat, translation):
        return {"name": name, "translation": tidy_list(translation), "rotation": tidy_list(UPRIGHT, 9),
                "extensions": {"KILN_quadric": {"primitive": primitive, "material": mat}}}

    nodes = [
        {"name": "cornell_box", "children": [1, 9]},                                       # 0
        {"name": "room", "children": [2, 3, 4, 5, 6, 7, 8, 10, 14]},                      # 1
        {"name": "floor", "mesh": 4, "translation": [0.0, 0.0, mid_z],                     # 2
         "rotation": q(x_axis, -90.0), "scale": [2.0, depth, 1.0]},
        {"name": "ceiling", "mesh": 5, "translation": [0.0, 2.0, 0.0],                     # 3
         "rotation": q(x_axis, 90.0)},
        {"name": "back_wall", "mesh": 0, "translation": [0.0, 1.0, -1.0],                  # 4
         "scale": [2.0, 2.0, 1.0]},
        {"name": "front_wall", "mesh": 0, "translation": [0.0, 1.0, ROOM_FRONT],           # 5
         "rotation": q(y_axis, 180.0), "scale": [2.0, 2.0, 1.0]},
        {"name": "left_wall_red", "mesh": 1, "matrix": to_gltf_matrix(left_wall_matrix)},  # 6
        {"name": "right_wall_green", "mesh": 2, "translation": [1.0, 1.0, mid_z],          # 7
         "rotation": q(y_axis, -90.0), "scale": [depth, 2.0, 1.0]},
        {"name": "light_panel", "mesh": 3, "translation": [0.0, PANEL_HEIGHT, 0.0],        # 8
         "rotation": q(x_axis, 90.0), "scale": [0.7, 0.7, 1.0]},
        {"name": "objects", "translation": [0.0, -SINK, 0.0], "children": [11, 12, 13, 17]},  # 9
        {"name": "mirror", "mesh": 6,                                                     # 10
         "translation": tidy_list([(a + b) / 2 for a, b in zip(MIRROR_MIN, MIRROR_MAX)]),
         "scale": tidy_list([b - a for a, b in zip(MIRROR_MIN, MIRROR_MAX)])},
        quadric("glass_column", 0, 6, [-0.2, 0.0, 0.55]),                                  # 11
        {"name": "blue_ball", "translation": [0.45, 0.24, 0.15],                           # 12
         "extensions": {"KILN_quadric": {"primitive": 1, "material": 7}}},
        quadric("yellow_ring", 2, 8, [-0.55, 0.065, -0.45]),                               # 13
        {"name": "ceiling_light", "translation": KEY_LIGHT,                               # 14
         "extensions": {"KHR_lights_punctual": {"light": 0}}},
        {"name": "main", "camera": 0, "translation": CAMERA,                              # 15
         "rotation": q(x_axis, CAMERA_PITCH)},
        {"name": "fill_light", "translation": FILL_LIGHT,                                 # 16
         "extensions": {"KHR_lights_punctual": {"light": 1}}},
        quadric("orange_cone", 3, 9, [0.05, 0.0, -0.6]),                                  # 17
    ]

    gltf = {
        "asset": {"version": "2.0", "generator": GENERATOR,
                  "copyright": "Generated procedurally; no third-party content"},
        "extensionsUsed": ["KHR_lights_punctual", "KHR_materials_emissive_strength",
                           "KHR_materials_transmission", "KHR_materials_ior", "KHR_materials_volume",
                           "KHR_texture_transform", "KILN_quadric"],
        "extensions": {
            "KHR_lights_punctual": {"lights": [
                {"name": "ceiling_light", "type": "point", "color": [1.0, 0.95, 0.88],
                 "intensity": 5.0},
                {"name": "fill_light", "type": "point", "color": [1.0, 1.0, 1.0],
                 "intensity": 1.8}]},
            "KILN_quadric": {"primitives": QUADRICS},
        },
        "scene": 0,
        "scenes": [{"name": "cornell_box", "nodes": [0, 15, 16]}],
        "nodes": nodes,
        "cameras": [{"name": "main", "type": "perspective",
                     "perspective": {"yfov": 0.75, "aspectRatio": 1.333333,
                                     "znear": 0.05, "zfar": 100.0}}],
        "meshes": meshes,
        "materials": materials,
        "textures": [{"name": "checker", "sampler": 0, "source": 0}],
        "images": [{"name": "checker", "uri": PNG_NAME, "mimeType": "image/png"}],
        "samplers": [{"name": "repeat_linear", "magFilter": LINEAR, "minFilter": LINEAR,
                      "wrapS": REPEAT, "wrapT": REPEAT}],
        "buffers": [{"name": "cornell_box", "uri": BIN_NAME, "byteLength": len(buf.data)}],
        "bufferViews": buf.buffer_views,
        "accessors": buf.accessors,
    }
    return gltf, bytes(buf.data)


# --------------------------------------------------------------------------------------------
# Validation (reads the written files back)

def read_accessor(gltf, bin_data, index):
    acc = gltf["accessors"][index]
    view = gltf["bufferViews"][acc["bufferView"]]
    n = TYPE_COUNT[acc["type"]]
    csize = COMPONENT_SIZE[acc["componentType"]]
    elem = n * csize
    stride = view.get("byteStride", elem)
    start = view.get("byteOffset", 0) + acc.get("byteOffset", 0)
    fmt = "<%d%s" % (n, COMPONENT_FORMAT[acc["componentType"]])
    return [struct.unpack_from(fmt, bin_data, start + i * stride) for i in range(acc["count"])]


def world_matrices(gltf):
    out = {}

    def visit(i, parent):
        m = mat_mul(parent, node_local_matrix(gltf["nodes"][i]))
        assert i not in out, "node %d reached twice" % i
        out[i] = m
        for c in gltf["nodes"][i].get("children", []):
            visit(c, m)

    for root in gltf["scenes"][gltf.get("scene", 0)]["nodes"]:
        visit(root, identity())
    return out


def det3(m):
    return (m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
            - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]))


def validate(out_dir):
    errors = []

    def check(cond, msg):
        if not cond:
            errors.append(msg)

    with open(os.path.join(out_dir, GLTF_NAME), "r", encoding="utf-8") as f:
        gltf = json.load(f)
    check(gltf["asset"]["version"] == "2.0", "asset.version")
    buffer = gltf["buffers"][0]
    with open(os.path.join(out_dir, buffer["uri"]), "rb") as f:
        bin_data = f.read()
    check(len(bin_data) == buffer["byteLength"], "buffer byteLength %d != file size %d"
          % (buffer["byteLength"], len(bin_data)))
    for image in gltf["images"]:
        with open(os.path.join(out_dir, image["uri"]), "rb") as f:
            png = f.read()
        check(png[:8] == b"\x89PNG\r\n\x1a\n", "PNG signature of " + image["uri"])
        w, h, depth, ctype = struct.unpack(">IIBB", png[16:26])
        check((depth, ctype) == (8, 2), "PNG is not 8-bit RGB")
        check(len(zlib.decompress(png[41:41 + struct.unpack(">I", png[33:37])[0]]))
              == h * (1 + 3 * w), "PNG IDAT size")

    for i, view in enumerate(gltf["bufferViews"]):
        off, ln = view.get("byteOffset", 0), view["byteLength"]
        check(off % 4 == 0, "bufferView %d offset not 4-byte aligned" % i)
        check(off + ln <= len(bin_data), "bufferView %d exceeds the buffer" % i)
    for i, acc in enumerate(gltf["accessors"]):
        view = gltf["bufferViews"][acc["bufferView"]]
        csize = COMPONENT_SIZE[acc["componentType"]]
        elem = TYPE_COUNT[acc["type"]] * csize
        stride = view.get("byteStride", elem)
        end = acc.get("byteOffset", 0) + stride * (acc["count"] - 1) + elem
        check(end <= view["byteLength"], "accessor %d exceeds its bufferView" % i)
        check((view.get("byteOffset", 0) + acc.get("byteOffset", 0)) % csize == 0,
              "accessor %d misaligned" % i)

    triangles = 0
    seen_prims = set()
    for mi, mesh in enumerate(gltf["meshes"]):
        for prim in mesh["primitives"]:
            a = prim["attributes"]
            key = (a["POSITION"], prim["indices"])
            pos = read_accessor(gltf, bin_data, a["POSITION"])
            nrm = read_accessor(gltf, bin_data, a["NORMAL"])
            uv = read_accessor(gltf, bin_data, a["TEXCOORD_0"])
            idx = [t[0] for t in read_accessor(gltf, bin_data, prim["indices"])]
            pacc = gltf["accessors"][a["POSITION"]]
            check(gltf["bufferViews"][gltf["accessors"][a["POSITION"]]["bufferView"]]["target"]
                  == ARRAY_BUFFER, "POSITION view target")
            check(gltf["bufferViews"][gltf["accessors"][prim["indices"]]["bufferView"]]["target"]
                  == ELEMENT_ARRAY_BUFFER, "indices view target")
            for k in range(3):
                check(pacc["min"][k] == min(p[k] for p in pos), "mesh %d POSITION min" % mi)
                check(pacc["max"][k] == max(p[k] for p in pos), "mesh %d POSITION max" % mi)
            check(len(nrm) == len(pos) == len(uv), "mesh %d attribute counts differ" % mi)
            check(all(i < len(pos) for i in idx), "mesh %d index out of range" % mi)
            check(len(idx) % 3 == 0, "mesh %d index count not a multiple of 3" % mi)
            check(all(abs(length(n) - 1.0) < 1e-6 for n in nrm), "mesh %d normal not unit" % mi)
            for t in range(0, len(idx), 3):
                i0, i1, i2 = idx[t:t + 3]
                g = cross(sub(pos[i1], pos[i0]), sub(pos[i2], pos[i0]))
                check(length(g) > 1e-9, "mesh %d triangle %d degenerate" % (mi, t // 3))
                check(all(dot(g, nrm[i]) > 0 for i in (i0, i1, i2)),
                      "mesh %d triangle %d winding disagrees with its normals" % (mi, t // 3))
            if key not in seen_prims:
                seen_prims.add(key)
            triangles += len(idx) // 3

    # World-space checks: walls face the inside of the room, everything lies inside it, the
    # objects stand on the floor without touching each other, the lights are inside the room.
    world = world_matrices(gltf)
    centre = [0.0, 1.0, (ROOM_FRONT - 1.0) / 2.0]
    room_lo, room_hi = [-1.0, 0.0, -1.0], [1.0, PANEL_HEIGHT, ROOM_FRONT]
    mesh_users = {}
    object_bounds = {}
    definitions = gltf["extensions"]["KILN_quadric"]["primitives"]
    print("nodes (world space):")
    for i, node in enumerate(gltf["nodes"]):
        m = world[i]
        origin = transform_point(m, [0.0, 0.0, 0.0])
        desc = ""
        inside = lambda p: all(room_lo[k] - 1e-6 <= p[k] <= room_hi[k] + 1e-6 for k in range(3))
        if "mesh" in node:
            mesh_users.setdefault(node["mesh"], []).append(node["name"])
            mesh = gltf["meshes"][node["mesh"]]
            check(det3(m) > 0, "node %s mirrors its mesh" % node["name"])
            pos = read_accessor(gltf, bin_data, mesh["primitives"][0]["attributes"]["POSITION"])
            wp = [transform_point(m, p) for p in pos]
            lo = [min(p[k] for p in wp) for k in range(3)]
            hi = [max(p[k] for p in wp) for k in range(3)]
            check(inside(lo) and inside(hi), "node %s leaves the room" % node["name"])
            n = normalize(transform_dir(m, [0.0, 0.0, 1.0]))
            if mesh["name"].startswith("wall") or mesh["name"] in ("floor_checker", "ceiling"):
                check(dot(n, sub(centre, origin)) > 0, "wall %s faces outwards" % node["name"])
            if mesh["name"] == "light_panel":
                check(n[1] < -0.999 and lo[1] > 2.0, "the light panel must face down from above the ceiling")
            desc = "mesh %-13s bounds (%5.2f %5.2f %5.2f)..(%5.2f %5.2f %5.2f) normal (%+.0f %+.0f %+.0f)" % (
                mesh["name"], *lo, *hi, *n)
        elif "camera" in node:
            fwd = normalize(transform_dir(m, [0.0, 0.0, -1.0]))
            check(inside(origin), "the camera is outside the room")
            desc = "camera, looks along (%+.2f %+.2f %+.2f)" % tuple(fwd)
        elif "KILN_quadric" in node.get("extensions", {}):
            ext = node["extensions"]["KILN_quadric"]
            # Bounds from the node's own translation plus its parents' (translations only here).
            local = dict(node)
            local["translation"] = origin
            lo, hi = quadric_bounds(definitions[ext["primitive"]], local)
            check(inside([lo[0], max(lo[1], 0.0), lo[2]]) and inside(hi), "quadric %s leaves the room" % node["name"])
            check(-2 * SINK <= lo[1] < 0.0, "quadric %s does not stand on the floor" % node["name"])
            object_bounds[node["name"]] = (lo, hi)
            desc = "quadric %-13s bounds (%5.2f %5.2f %5.2f)..(%5.2f %5.2f %5.2f)" % (
                definitions[ext["primitive"]]["name"], *lo, *hi)
        elif "extensions" in node:
            check(inside(origin) and origin[1] < 2.0, "light %s is outside the room" % node["name"])
            desc = "point light"
        print("  %-18s at (%6.3f %6.3f %6.3f)  %s" % (node["name"], *origin, desc))
    check(any(len(v) > 1 for v in mesh_users.values()), "no mesh is instanced")
    names = sorted(object_bounds)
    for a in range(len(names)):
        for b in range(a + 1, len(names)):
            (alo, ahi), (blo, bhi) = object_bounds[names[a]], object_bounds[names[b]]
            check(any(ahi[k] < blo[k] or bhi[k] < alo[k] for k in range(3)),
                  "the bounds of %s and %s overlap" % (names[a], names[b]))

    print("summary: %d nodes, %d meshes (%d unique geometries), %d materials, %d accessors, "
          "%d bufferViews, %d triangles drawn, %s = %d bytes"
          % (len(gltf["nodes"]), len(gltf["meshes"]), len(seen_prims), len(gltf["materials"]),
             len(gltf["accessors"]), len(gltf["bufferViews"]), triangles, buffer["uri"],
             len(bin_data)))
    for mi, users in sorted(mesh_users.items()):
        if len(users) > 1:
            print("instanced: mesh %r placed by %s" % (gltf["meshes"][mi]["name"], ", ".join(users)))
    shared = {}
    for mesh in gltf["meshes"]:
        for prim in mesh["primitives"]:
            shared.setdefault(prim["attributes"]["POSITION"], []).append(mesh["name"])
    for acc, names in sorted(shared.items()):
        print("shared geometry: accessor %d (%s) used by meshes %s"
              % (acc, gltf["accessors"][acc]["name"], ", ".join(names)))
    if errors:
        for e in errors:
            print("ERROR:", e)
        return False
    print("validation: OK (accessor ranges, alignment, index ranges, unit normals, winding, "
          "wall orientation, bounds)")
    return True


# --------------------------------------------------------------------------------------------

def main():
    repo_root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out-dir", default=os.path.join(repo_root, "scenes"))
    parser.add_argument("--no-validate", action="store_true")
    args = parser.parse_args()

    gltf, bin_data = build_scene()
    os.makedirs(args.out_dir, exist_ok=True)
    with open(os.path.join(args.out_dir, GLTF_NAME), "w", encoding="utf-8", newline="\n") as f:
        f.write(json.dumps(gltf, indent=2) + "\n")
    with open(os.path.join(args.out_dir, BIN_NAME), "wb") as f:
        f.write(bin_data)
    with open(os.path.join(args.out_dir, PNG_NAME), "wb") as f:
        f.write(make_checker_png())
    print("wrote %s, %s, %s in %s" % (GLTF_NAME, BIN_NAME, PNG_NAME, args.out_dir))
    if not args.no_validate and not validate(args.out_dir):
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
