#!/usr/bin/env python3
"""Write the two animated scenes of the sequence benchmark (bench/sequence/README.md) into a folder:

  rigid_boxes.gltf   400 boxes on a 20 x 20 grid, each spinning and bobbing (node rotation and
                     translation channels), one point light, one camera: per-frame overhead of
                     rigid animation (instances moved, top level recommitted).
  skinned_tube.gltf  a tube of about 100k triangles skinned to two joints, the upper one bending
                     the tube over one second: per-frame cost of skinning and refitting one
                     deformed mesh.

Usage: make_sequence_scenes.py FOLDER
"""
import base64
import json
import math
import struct
import sys
from pathlib import Path


class Buffer:
    """One binary buffer whose views and accessors collect as the scene is written."""

    def __init__(self):
        self.data = bytearray()
        self.views = []
        self.accessors = []

    def add(self, values, fmt, component, kind, count, minmax=None, target=None):
        while len(self.data) % 4:
            self.data.append(0)
        offset = len(self.data)
        self.data += struct.pack("<%d%s" % (len(values), fmt), *values)
        view = {"buffer": 0, "byteOffset": offset, "byteLength": len(self.data) - offset}
        if target:
            view["target"] = target
        self.views.append(view)
        accessor = {"bufferView": len(self.views) - 1, "componentType": component, "count": count, "type": kind}
        if minmax:
            accessor["min"], accessor["max"] = minmax
        self.accessors.append(accessor)
        return len(self.accessors) - 1

    def finish(self, doc):
        doc["buffers"] = [{"byteLength": len(self.data),
                           "uri": "data:application/octet-stream;base64," + base64.b64encode(self.data).decode()}]
        doc["bufferViews"] = self.views
        doc["accessors"] = self.accessors
        return doc


def positions_accessor(buf, points):
    flat = [c for p in points for c in p]
    lo = [min(p[i] for p in points) for i in range(3)]
    hi = [max(p[i] for p in points) for i in range(3)]
    return buf.add(flat, "f", 5126, "VEC3", len(points), (lo, hi), 34962)


def box_mesh(buf):
    points, normals, indices = [], [], []
    for axis in range(3):
        for sign in (-1.0, 1.0):
            n = [0.0, 0.0, 0.0]
            n[axis] = sign
            u, v = [(axis + 1) % 3, (axis + 2) % 3]
            base = len(points)
            for a, b in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
                p = [0.0, 0.0, 0.0]
                p[axis], p[u], p[v] = 0.4 * sign, 0.4 * a, 0.4 * b
                points.append(p)
                normals.append(n)
            quad = [base, base + 1, base + 2, base, base + 2, base + 3]
            indices += quad if sign > 0 else [quad[0], quad[2], quad[1], quad[3], quad[5], quad[4]]
    return {"primitives": [{"attributes": {"POSITION": positions_accessor(buf, points),
                                           "NORMAL": buf.add([c for n in normals for c in n], "f", 5126, "VEC3",
                                                             len(normals), None, 34962)},
                            "indices": buf.add(indices, "I", 5125, "SCALAR", len(indices), None, 34963),
                            "material": 0}]}


def rigid_boxes(path):
    buf = Buffer()
    doc = {"asset": {"version": "2.0", "generator": "kiln bench/sequence"},
           "extensionsUsed": ["KHR_lights_punctual"],
           "extensions": {"KHR_lights_punctual": {"lights": [{"type": "point", "intensity": 2000.0}]}},
           "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.5, 0.3, 1.0], "roughnessFactor": 0.5,
                                                   "metallicFactor": 0.0}}],
           "meshes": [box_mesh(buf)], "nodes": [], "animations": []}
    keys = [i / 24.0 for i in range(25)]
    times = buf.add(keys, "f", 5126, "SCALAR", len(keys), ([0.0], [1.0]))
    samplers, channels = [], []
    for j in range(20):
        for i in range(20):
            node = len(doc["nodes"])
            x, z = i - 9.5, j - 9.5
            doc["nodes"].append({"mesh": 0, "translation": [x, 0.0, z]})
            phase = 0.3 * (i + 2 * j)
            spin = []
            bob = []
            for t in keys:
                a = 2.0 * math.pi * t + phase
                spin += [0.0, math.sin(a / 2), 0.0, math.cos(a / 2)]
                bob += [x, 0.3 * math.sin(a), z]
            samplers.append({"input": times, "output": buf.add(spin, "f", 5126, "VEC4", len(keys))})
            channels.append({"sampler": len(samplers) - 1, "target": {"node": node, "path": "rotation"}})
            samplers.append({"input": times, "output": buf.add(bob, "f", 5126, "VEC3", len(keys))})
            channels.append({"sampler": len(samplers) - 1, "target": {"node": node, "path": "translation"}})
    doc["animations"].append({"name": "boxes", "samplers": samplers, "channels": channels})
    doc["nodes"].append({"extensions": {"KHR_lights_punctual": {"light": 0}}, "translation": [0.0, 12.0, 4.0]})
    doc["cameras"] = [{"type": "perspective", "perspective": {"yfov": 0.9, "znear": 0.1, "aspectRatio": 4 / 3}}]
    pitch = -0.7
    doc["nodes"].append({"camera": 0, "translation": [0.0, 14.0, 16.0],
                         "rotation": [math.sin(pitch / 2), 0.0, 0.0, math.cos(pitch / 2)]})
    doc["scenes"] = [{"nodes": list(range(len(doc["nodes"])))}]
    doc["scene"] = 0
    Path(path).write_text(json.dumps(buf.finish(doc)))


def skinned_tube(path, rings=500, sides=100):
    """rings x sides quads (2 triangles each): 500 x 100 -> 100k triangles, height 4 along +Y."""
    buf = Buffer()
    points, normals, joints, weights, indices = [], [], [], [], []
    for r in range(rings + 1):
        y = 4.0 * r / rings
        w1 = min(max((y - 1.5) / 1.0, 0.0), 1.0)  # the upper joint takes over between y = 1.5 and 2.5
        for s in range(sides):
            a = 2.0 * math.pi * s / sides
            points.append([0.3 * math.cos(a), y, 0.3 * math.sin(a)])
            normals.append([math.cos(a), 0.0, math.sin(a)])
            joints += [0, 1, 0, 0]
            weights += [1.0 - w1, w1, 0.0, 0.0]
    for r in range(rings):
        for s in range(sides):
            a, b = r * sides + s, r * sides + (s + 1) % sides
            c, d = a + sides, b + sides
            indices += [a, c, b, b, c, d]
    keys = [i / 24.0 for i in range(25)]
    bend = []
    for t in keys:
        angle = 1.2 * math.sin(math.pi * t)
        bend += [0.0, 0.0, math.sin(angle / 2), math.cos(angle / 2)]
    ibm = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1,
           1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -2, 0, 1]
    doc = {"asset": {"version": "2.0", "generator": "kiln bench/sequence"},
           "extensionsUsed": ["KHR_lights_punctual"],
           "extensions": {"KHR_lights_punctual": {"lights": [{"type": "directional", "intensity": 3.0}]}},
           "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [0.3, 0.6, 0.8, 1.0], "roughnessFactor": 0.4,
                                                   "metallicFactor": 0.0}}]}
    attributes = {"POSITION": positions_accessor(buf, points),
                  "NORMAL": buf.add([c for n in normals for c in n], "f", 5126, "VEC3", len(normals), None, 34962),
                  "JOINTS_0": buf.add(joints, "B", 5121, "VEC4", len(points), None, 34962),
                  "WEIGHTS_0": buf.add(weights, "f", 5126, "VEC4", len(points), None, 34962)}
    doc["meshes"] = [{"primitives": [{"attributes": attributes, "material": 0,
                                      "indices": buf.add(indices, "I", 5125, "SCALAR", len(indices), None, 34963)}]}]
    doc["skins"] = [{"joints": [1, 2], "inverseBindMatrices": buf.add(ibm, "f", 5126, "MAT4", 2)}]
    doc["nodes"] = [{"mesh": 0, "skin": 0}, {"children": [2]}, {"translation": [0.0, 2.0, 0.0]},
                    {"extensions": {"KHR_lights_punctual": {"light": 0}}, "rotation": [-0.38, 0.0, 0.0, 0.92]},
                    {"camera": 0, "translation": [0.0, 2.0, 9.0]}]
    times = buf.add(keys, "f", 5126, "SCALAR", len(keys), ([0.0], [1.0]))
    doc["animations"] = [{"name": "bend", "samplers": [{"input": times, "output": buf.add(bend, "f", 5126, "VEC4",
                                                                                         len(keys))}],
                          "channels": [{"sampler": 0, "target": {"node": 2, "path": "rotation"}}]}]
    doc["cameras"] = [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1, "aspectRatio": 4 / 3}}]
    doc["scenes"] = [{"nodes": [0, 1, 3, 4]}]
    doc["scene"] = 0
    Path(path).write_text(json.dumps(buf.finish(doc)))


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    folder = Path(sys.argv[1])
    folder.mkdir(parents=True, exist_ok=True)
    rigid_boxes(folder / "rigid_boxes.gltf")
    skinned_tube(folder / "skinned_tube.gltf")


if __name__ == "__main__":
    main()
