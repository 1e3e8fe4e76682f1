#!/usr/bin/env python3
"""Generate kiln's demo scene: scenes/cornell_box.gltf, scenes/cornell_box.bin, scenes/checker.png.

A Cornell-box-like room (metres, +Y up), open at the front (+Z) where the camera "main" stands:

  room        x in [-1, 1], y in [0, 2], z in [-1, 1]
  walls       white floor, ceiling and back wall; red left wall (x = -1); green right wall (x = +1)
  tall box    mirror (metallic 1, roughness 0), back left, turned +40 degrees about Y so that its
              two visible faces reflect the red wall and the checker box (not the open front)
  short box   checkerboard baseColorTexture, front right, rotated -18 degrees about Y
  ceiling     small emissive panel flush under the ceiling (its shadow on the ceiling stays a thin rim), point light (KHR_lights_punctual) below it
  fill light  weaker point light outside the open front, up and to the right of the camera: without
              it the box faces turned to the camera would be black (Whitted shading has no
              indirect light, and the ceiling light is behind those faces' planes)

Geometry is two small meshes stored once: a unit quad (the walls and the light panel) and a unit
cube with flat per-face normals (24 vertices). Materials are per primitive in glTF, so each
material gets its own mesh whose primitive points at the shared accessors; the white wall mesh is
placed by three nodes (floor, ceiling, back wall). Transforms use both TRS and matrix forms, under
parent nodes whose own transforms matter.

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
CHECKER_COLOR_A = (235, 190, 40)   # sRGB mustard yellow
CHECKER_COLOR_B = (40, 70, 150)    # sRGB slate blue


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
        pbr["baseColorTexture"] = {"index": extra["texture"], "texCoord": 0}
    if "emissive" in extra:
        m["emissiveFactor"] = tidy_list(extra["emissive"], 4)
    if "emissive_strength" in extra:
        m["extensions"] = {"KHR_materials_emissive_strength":
                           {"emissiveStrength": extra["emissive_strength"]}}
    return m


def build_scene():
    buf = BufferBuilder()
    quad_verts, quad_indices = make_quad()
    cube_verts, cube_indices = make_cube()
    quad_attrs, quad_idx = buf.add_mesh_data(quad_verts, quad_indices, "quad")
    cube_attrs, cube_idx = buf.add_mesh_data(cube_verts, cube_indices, "cube")

    materials = [
        material("white", (0.725, 0.71, 0.68), 0.0, 1.0),                     # 0
        material("red", (0.63, 0.065, 0.05), 0.0, 1.0),                       # 1
        material("green", (0.14, 0.45, 0.091), 0.0, 1.0),                     # 2
        material("mirror", (0.95, 0.95, 0.95), 1.0, 0.0),                     # 3
        material("checker", (1.0, 1.0, 1.0), 0.0, 0.6, texture=0),            # 4
        material("light_panel", (0.0, 0.0, 0.0), 0.0, 1.0,                    # 5
                 emissive=(1.0, 0.95, 0.88), emissive_strength=4.0),
    ]

    def mesh(name, attrs, idx, mat):
        return {"name": name, "primitives": [
            {"attributes": dict(attrs), "indices": idx, "material": mat, "mode": 4}]}

    meshes = [
        mesh("wall_white", quad_attrs, quad_idx, 0),      # 0: floor, ceiling, back wall
        mesh("wall_red", quad_attrs, quad_idx, 1),        # 1
        mesh("wall_green", quad_attrs, quad_idx, 2),      # 2
        mesh("light_panel", quad_attrs, quad_idx, 5),     # 3
        mesh("cube_mirror", cube_attrs, cube_idx, 3),     # 4
        mesh("cube_checker", cube_attrs, cube_idx, 4),    # 5
    ]

    x_axis, y_axis = [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]

    def q(axis, deg):
        return tidy_list(quat_axis_angle(axis, deg), 9)

    # The room group maps the unit cube [-0.5, 0.5]^3 onto x,z in [-1, 1], y in [0, 2]:
    # a matrix node (uniform scale 2, then up by 1). The walls are unit quads inside it.
    room_matrix = mat_mul(mat_translate([0.0, 1.0, 0.0]), mat_scale([2.0, 2.0, 2.0]))
    left_wall_matrix = mat_mul(mat_translate([-0.5, 0.0, 0.0]),
                               mat_rotate_quat(quat_axis_angle(y_axis, 90.0)))
    # The mirror box: tall block (0.6 x 1.2 x 0.6) at the back left, turned +40 degrees about Y,
    # given as a matrix. It sits inside the "objects" group, which is translated by (0, 0, -0.05).
    tall_matrix = mat_mul(mat_translate([-0.42, 0.6, -0.25]),
                          mat_mul(mat_rotate_quat(quat_axis_angle(y_axis, 40.0)),
                                  mat_scale([0.6, 1.2, 0.6])))

    nodes = [
        {"name": "cornell_box", "children": [1, 8]},                                     # 0
        {"name": "room", "matrix": to_gltf_matrix(room_matrix),                          # 1
         "children": [2, 3, 4, 5, 6, 7]},
        {"name": "floor", "mesh": 0, "translation": [0.0, -0.5, 0.0],                    # 2
         "rotation": q(x_axis, -90.0)},
        {"name": "ceiling", "mesh": 0, "translation": [0.0, 0.5, 0.0],                   # 3
         "rotation": q(x_axis, 90.0)},
        {"name": "back_wall", "mesh": 0, "translation": [0.0, 0.0, -0.5]},              # 4
        {"name": "left_wall_red", "mesh": 1, "matrix": to_gltf_matrix(left_wall_matrix)},  # 5
        {"name": "right_wall_green", "mesh": 2, "translation": [0.5, 0.0, 0.0],         # 6
         "rotation": q(y_axis, -90.0)},
        {"name": "light_panel", "mesh": 3, "translation": [0.0, 0.499, 0.0],             # 7
         "rotation": q(x_axis, 90.0), "scale": [0.25, 0.25, 0.25]},
        {"name": "objects", "translation": [0.0, 0.0, -0.05], "children": [9, 10, 11]},  # 8
        {"name": "tall_box_mirror", "mesh": 4, "matrix": to_gltf_matrix(tall_matrix)},   # 9
        {"name": "short_box_checker", "mesh": 5, "translation": [0.42, 0.3, 0.35],       # 10
         "rotation": q(y_axis, -18.0), "scale": [0.6, 0.6, 0.6]},
        {"name": "ceiling_light", "translation": [0.0, 1.9, 0.05],                       # 11
         "extensions": {"KHR_lights_punctual": {"light": 0}}},
        {"name": "main", "camera": 0, "translation": [0.0, 1.0, 3.9]},                   # 12
        {"name": "fill_light", "translation": [0.6, 1.7, 2.4],                           # 13
         "extensions": {"KHR_lights_punctual": {"light": 1}}},
    ]

    gltf = {
        "asset": {"version": "2.0", "generator": GENERATOR,
                  "copyright": "Generated procedurally; no third-party content"},
        "extensionsUsed": ["KHR_lights_punctual", "KHR_materials_emissive_strength"],
        "extensions": {"KHR_lights_punctual": {"lights": [
            {"name": "ceiling_light", "type": "point", "color": [1.0, 0.95, 0.88],
             "intensity": 12.0},
            {"name": "fill_light", "type": "point", "color": [1.0, 1.0, 1.0],
             "intensity": 6.0}]}},
        "scene": 0,
        "scenes": [{"name": "cornell_box", "nodes": [0, 12, 13]}],
        "nodes": nodes,
        "cameras": [{"name": "main", "type": "perspective",
                     "perspective": {"yfov": 0.7, "aspectRatio": 1.333333,
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

    # World-space checks: walls face the inside of the room, everything lies inside it.
    world = world_matrices(gltf)
    centre = [0.0, 1.0, 0.0]
    mesh_users = {}
    box_bounds = {}
    print("nodes (world space):")
    for i, node in enumerate(gltf["nodes"]):
        m = world[i]
        origin = transform_point(m, [0.0, 0.0, 0.0])
        desc = ""
        if "mesh" in node:
            mesh_users.setdefault(node["mesh"], []).append(node["name"])
            mesh = gltf["meshes"][node["mesh"]]
            check(det3(m) > 0, "node %s mirrors its mesh" % node["name"])
            pos = read_accessor(gltf, bin_data, mesh["primitives"][0]["attributes"]["POSITION"])
            wp = [transform_point(m, p) for p in pos]
            lo = [min(p[k] for p in wp) for k in range(3)]
            hi = [max(p[k] for p in wp) for k in range(3)]
            check(all(-1.0 - 1e-6 <= lo[k] and hi[k] <= (2.0 if k == 1 else 1.0) + 1e-6
                      and (k != 1 or lo[k] >= -1e-6) for k in range(3)),
                  "node %s leaves the room" % node["name"])
            if mesh["name"].startswith("cube"):
                box_bounds[i] = (lo, hi)
            if mesh["name"].startswith("wall"):
                n = normalize(transform_dir(m, [0.0, 0.0, 1.0]))
                check(dot(n, sub(centre, origin)) > 0, "wall %s faces outwards" % node["name"])
                desc = "normal (%+.0f %+.0f %+.0f)" % tuple(n)
            desc = "mesh %-13s bounds (%5.2f %5.2f %5.2f)..(%5.2f %5.2f %5.2f) %s" % (
                mesh["name"], *lo, *hi, desc)
        elif "camera" in node:
            fwd = normalize(transform_dir(m, [0.0, 0.0, -1.0]))
            desc = "camera, looks along (%+.2f %+.2f %+.2f)" % tuple(fwd)
        elif "extensions" in node:
            desc = "point light"
        print("  %-18s at (%6.3f %6.3f %6.3f)  %s" % (node["name"], *origin, desc))
    check(any(len(v) > 1 for v in mesh_users.values()), "no mesh is instanced")
    boxes = [b for b in box_bounds.values()]
    for a in range(len(boxes)):
        for b in range(a + 1, len(boxes)):
            check(any(boxes[a][1][k] < boxes[b][0][k] or boxes[b][1][k] < boxes[a][0][k]
                      for k in range(3)), "the boxes' bounds overlap")

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
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
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
