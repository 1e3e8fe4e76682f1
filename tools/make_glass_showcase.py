#!/usr/bin/env python3
"""Generate scenes/glass_showcase.gltf (single file, buffer as a data URI) and its environment map
scenes/glass_showcase_sky.hdr: a glass sphere (KHR_materials_transmission + KHR_materials_ior +
KHR_materials_volume, faintly green absorption), a mirror sphere, a thin-walled tinted glass pane
and a glass slab on a two-tone diffuse floor, lit by a directional "sun", metres, +Y up.

Render: kiln render scenes/glass_showcase.gltf -o out.exr \
            --environment scenes/glass_showcase_sky.hdr --show-background

Python 3 standard library only; deterministic output.
Usage: python3 tools/make_glass_showcase.py [--out-dir DIR]
"""

import argparse
import base64
import json
import math
import os
import struct
import subprocess
import sys


def uv_sphere(rings=32, segments=64):
    """Unit sphere: positions (= normals) and counter-clockwise (outward) triangles."""
    positions, indices = [], []
    for r in range(rings + 1):
        theta = math.pi * r / rings
        for s in range(segments + 1):
            phi = 2.0 * math.pi * s / segments
            positions.append((math.sin(theta) * math.sin(phi), math.cos(theta), math.sin(theta) * math.cos(phi)))
    for r in range(rings):
        for s in range(segments):
            a = r * (segments + 1) + s
            b = a + segments + 1
            if r != 0:
                indices += [a, b, a + 1]
            if r != rings - 1:
                indices += [a + 1, b, b + 1]
    return positions, positions, indices


def box():
    """Unit cube [-0.5, 0.5]^3 with flat per-face normals (24 vertices), outward winding."""
    positions, normals, indices = [], [], []
    for axis in range(3):
        for sign in (-1.0, 1.0):
            n = [0.0, 0.0, 0.0]
            n[axis] = sign
            u = [0.0, 0.0, 0.0]
            v = [0.0, 0.0, 0.0]
            u[(axis + 1) % 3] = 0.5
            v[(axis + 2) % 3] = 0.5
            base = len(positions)
            for du, dv in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
                positions.append(tuple(0.5 * n[i] + du * u[i] + dv * v[i] for i in range(3)))
                normals.append(tuple(n))
            quad = [base, base + 1, base + 2, base, base + 2, base + 3]
            if sign < 0:  # keep the winding counter-clockwise seen from outside
                quad = [base, base + 2, base + 1, base, base + 3, base + 2]
            indices += quad
    return positions, normals, indices


class builder:
    def __init__(self):
        self.bin = bytearray()
        self.doc = {"asset": {"version": "2.0", "generator": "kiln tools/make_glass_showcase.py"},
                    "buffers": [], "bufferViews": [], "accessors": [], "meshes": [], "materials": [],
                    "nodes": [], "scenes": [{"nodes": []}], "scene": 0,
                    "extensionsUsed": ["KHR_lights_punctual", "KHR_materials_transmission", "KHR_materials_ior",
                                       "KHR_materials_volume"],
                    "extensions": {"KHR_lights_punctual": {"lights": []}}}

    def accessor(self, values, fmt, gltf_type, component, count, target, minmax=None):
        while len(self.bin) % 4:
            self.bin.append(0)
        offset = len(self.bin)
        self.bin += struct.pack("<" + fmt * len(values), *values)
        self.doc["bufferViews"].append({"buffer": 0, "byteOffset": offset, "byteLength": len(self.bin) - offset,
                                        "target": target})
        acc = {"bufferView": len(self.doc["bufferViews"]) - 1, "componentType": component, "count": count,
               "type": gltf_type}
        if minmax:
            acc["min"], acc["max"] = minmax
        self.doc["accessors"].append(acc)
        return len(self.doc["accessors"]) - 1

    def mesh(self, shape, material):
        positions, normals, indices = shape
        flat_p = [c for p in positions for c in p]
        lo = [min(p[i] for p in positions) for i in range(3)]
        hi = [max(p[i] for p in positions) for i in range(3)]
        pos = self.accessor(flat_p, "f", "VEC3", 5126, len(positions), 34962, (lo, hi))
        nor = self.accessor([c for n in normals for c in n], "f", "VEC3", 5126, len(normals), 34962)
        idx = self.accessor(indices, "I", "SCALAR", 5125, len(indices), 34963)
        self.doc["meshes"].append({"primitives": [{"attributes": {"POSITION": pos, "NORMAL": nor}, "indices": idx,
                                                   "material": material}]})
        return len(self.doc["meshes"]) - 1

    def material(self, m):
        self.doc["materials"].append(m)
        return len(self.doc["materials"]) - 1

    def node(self, n):
        self.doc["nodes"].append(n)
        self.doc["scenes"][0]["nodes"].append(len(self.doc["nodes"]) - 1)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out-dir", default=os.path.join(os.path.dirname(__file__), "..", "scenes"))
    args = parser.parse_args()
    b = builder()
    floor_light = b.material({"name": "floor", "pbrMetallicRoughness": {"baseColorFactor": [0.7, 0.7, 0.68, 1],
                                                                        "metallicFactor": 0, "roughnessFactor": 0.9}})
    floor_dark = b.material({"name": "floor tiles", "pbrMetallicRoughness": {
        "baseColorFactor": [0.15, 0.2, 0.35, 1], "metallicFactor": 0, "roughnessFactor": 0.9}})
    glass = b.material({"name": "glass", "pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 1], "metallicFactor": 0,
                                                                  "roughnessFactor": 0},
                        "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1},
                                       "KHR_materials_ior": {"ior": 1.5},
                                       "KHR_materials_volume": {"thicknessFactor": 1, "attenuationDistance": 2.0,
                                                                "attenuationColor": [0.8, 0.95, 0.85]}}})
    mirror = b.material({"name": "mirror", "pbrMetallicRoughness": {"baseColorFactor": [0.95, 0.93, 0.9, 1],
                                                                    "metallicFactor": 1, "roughnessFactor": 0}})
    pane = b.material({"name": "tinted pane", "doubleSided": True,
                       "pbrMetallicRoughness": {"baseColorFactor": [1, 0.6, 0.3, 1], "metallicFactor": 0,
                                                "roughnessFactor": 0},
                       "extensions": {"KHR_materials_transmission": {"transmissionFactor": 0.9}}})
    cube = box()
    sphere = uv_sphere()
    tile_light = b.mesh(cube, floor_light)
    tile_dark = b.mesh(cube, floor_dark)
    for i in range(-3, 3):  # a 6 x 6 floor of 1 m tiles, alternating
        for j in range(-3, 3):
            b.node({"mesh": tile_dark if (i + j) % 2 else tile_light, "translation": [i + 0.5, -0.05, j + 0.5],
                    "scale": [1, 0.1, 1]})
    b.node({"mesh": b.mesh(sphere, glass), "translation": [-0.7, 0.6, 0.2], "scale": [0.6, 0.6, 0.6]})
    b.node({"mesh": b.mesh(sphere, mirror), "translation": [0.8, 0.5, -0.6], "scale": [0.5, 0.5, 0.5]})
    b.node({"mesh": b.mesh(cube, glass), "translation": [0.6, 0.25, 0.9], "scale": [0.8, 0.5, 0.15],
            "rotation": [0, math.sin(-0.3), 0, math.cos(-0.3)]})
    b.node({"mesh": b.mesh(cube, pane), "translation": [-0.2, 0.6, -1.3], "scale": [1.4, 1.2, 0.01]})
    b.doc["extensions"]["KHR_lights_punctual"]["lights"].append(
        {"name": "sun", "type": "directional", "intensity": 3.0, "color": [1, 0.96, 0.9]})
    # The sun: 30 degrees above the horizon, shining toward -Z after a turn (matches the sky's sun).
    pitch = math.radians(-30.0)
    yaw = math.radians(200.0)
    qy = (0.0, math.sin(yaw / 2), 0.0, math.cos(yaw / 2))
    qx = (math.sin(pitch / 2), 0.0, 0.0, math.cos(pitch / 2))
    q = (qy[3] * qx[0], qy[1] * qx[3], -qy[1] * qx[0], qy[3] * qx[3])  # qy * qx
    b.node({"name": "sun", "rotation": list(q), "extensions": {"KHR_lights_punctual": {"light": 0}}})
    b.doc["cameras"] = [{"name": "main", "type": "perspective",
                         "perspective": {"yfov": 0.7, "aspectRatio": 4 / 3, "znear": 0.05}}]
    look_pitch = math.radians(-18.0)
    b.node({"name": "camera", "camera": 0, "translation": [0.0, 1.6, 4.2],
            "rotation": [math.sin(look_pitch / 2), 0, 0, math.cos(look_pitch / 2)]})
    b.doc["buffers"].append({"byteLength": len(b.bin),
                             "uri": "data:application/octet-stream;base64," + base64.b64encode(b.bin).decode()})
    out = os.path.join(args.out_dir, "glass_showcase.gltf")
    with open(out, "w") as f:
        json.dump(b.doc, f, indent=1, sort_keys=True)
        f.write("\n")
    sky = os.path.join(args.out_dir, "glass_showcase_sky.hdr")
    subprocess.run([sys.executable, os.path.join(os.path.dirname(__file__), "make_environment_map.py"), sky,
                    "--width", "256"], check=True)
    print("wrote", out, "and", sky)


if __name__ == "__main__":
    main()
