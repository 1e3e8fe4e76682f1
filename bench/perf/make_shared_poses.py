#!/usr/bin/env python3
"""Writes GLBs of many nodes that deform one big mesh, for measuring what posing shares
(docs/performance.md, "Posed meshes"). The mesh is a grid of about --triangles triangles (180k by
default) skinned to three joints in a chain, with two morph targets; --nodes nodes (300) place it:

  shared_skin.glb    every node skins the mesh with the one skin: all are the same pose (glTF
                     ignores a skinned node's own transform), so one posed mesh serves them all
  shared_morph.glb   the mesh without its skin, morph weights (0.5, 0.25) on the mesh, each node
                     at its own place on a grid: one posed mesh placed by every node
  distinct_morph.glb the same, each node with weights of its own: every node its own posed mesh
  animated_skin.glb  shared_skin.glb whose middle joint bends over one second: the pose changes
                     with time, still one posed mesh for every node
  still_skin.glb     shared_skin.glb plus a camera that dollies over one second: the file is
                     animated, its skin never moves, so a sequence poses the mesh once

Measure with /usr/bin/time -f "%e s %M KB" kiln render FILE -o out.exr --spp 1.
Usage: make_shared_poses.py FOLDER [--nodes N] [--triangles T]
"""
import argparse
import json
import math
import os
import struct


class Blob:
    """One binary chunk whose views and accessors collect as the asset is written."""

    def __init__(self):
        self.data = bytearray()
        self.views = []
        self.accessors = []

    def add(self, raw, component, kind, count, minmax=None):
        while len(self.data) % 4:
            self.data.append(0)
        self.views.append({"buffer": 0, "byteOffset": len(self.data), "byteLength": len(raw)})
        self.data += raw
        accessor = {"bufferView": len(self.views) - 1, "componentType": component, "count": count, "type": kind}
        if minmax:
            accessor["min"], accessor["max"] = minmax
        self.accessors.append(accessor)
        return len(self.accessors) - 1


def grid(triangles):
    """A grid in the x-y plane from (0, -0.5) to (3, 0.5), about `triangles` triangles: positions,
    uint32 indices, and per vertex the joints and weights that skin it to three bones along x."""
    columns = max(1, int(math.sqrt(triangles / 2 * 3)))
    rows = max(1, triangles // (2 * columns))
    positions, joints, weights = bytearray(), bytearray(), bytearray()
    for j in range(rows + 1):
        for i in range(columns + 1):
            x, y = 3.0 * i / columns, -0.5 + j / rows
            positions += struct.pack("<3f", x, y, 0.0)
            bone = min(2, int(x))
            blend = min(1.0, max(0.0, x - bone - 0.5)) if bone < 2 else 0.0
            joints += struct.pack("<4B", bone, min(2, bone + 1), 0, 0)
            weights += struct.pack("<4f", 1.0 - blend, blend, 0.0, 0.0)
    indices = bytearray()
    for j in range(rows):
        for i in range(columns):
            a = j * (columns + 1) + i
            indices += struct.pack("<6I", a, a + 1, a + columns + 2, a, a + columns + 2, a + columns + 1)
    return bytes(positions), bytes(indices), bytes(joints), bytes(weights), (rows + 1) * (columns + 1)


def morph_deltas(vertices, axis, scale):
    """A target moving every vertex along one axis by `scale`."""
    delta = [0.0, 0.0, 0.0]
    delta[axis] = scale
    return struct.pack("<3f", *delta) * vertices


def asset(mesh_data, nodes, kind, animate=None):
    """The glTF document and binary chunk of one case."""
    positions, indices, joints, weights, vertices = mesh_data
    blob = Blob()
    pos = blob.add(positions, 5126, "VEC3", vertices, ([0, -0.5, 0], [3, 0.5, 0]))
    idx = blob.add(indices, 5125, "SCALAR", len(indices) // 4)
    attributes = {"POSITION": pos}
    skinned = kind.endswith("skin")
    if skinned:
        attributes["JOINTS_0"] = blob.add(joints, 5121, "VEC4", vertices)
        attributes["WEIGHTS_0"] = blob.add(weights, 5126, "VEC4", vertices)
    targets = [{"POSITION": blob.add(morph_deltas(vertices, 2, 0.5), 5126, "VEC3", vertices,
                                     ([0, 0, 0.5], [0, 0, 0.5]))},
               {"POSITION": blob.add(morph_deltas(vertices, 1, 0.25), 5126, "VEC3", vertices,
                                     ([0, 0.25, 0], [0, 0.25, 0]))}]
    primitive = {"attributes": attributes, "indices": idx, "material": 0, "targets": targets}
    doc = {
        "asset": {"version": "2.0", "generator": "bench/perf/make_shared_poses.py"},
        "scene": 0,
        "meshes": [{"primitives": [primitive], "weights": [0.5, 0.25]}],
        "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.5, 0.3, 1], "metallicFactor": 0}}],
        "nodes": [],
    }
    side = math.ceil(math.sqrt(nodes))
    for n in range(nodes):
        node = {"mesh": 0, "translation": [3.5 * (n % side), 1.5 * (n // side), 0]}
        if skinned:
            node["skin"] = 0
        if kind == "distinct_morph":
            node["weights"] = [n / nodes, 1.0 - n / nodes]
        doc["nodes"].append(node)
    roots = list(range(nodes))
    if skinned:
        # Three joints in a chain one unit apart along x; bind matrices undo their rest places.
        first = len(doc["nodes"])
        doc["nodes"] += [{"children": [first + 1]}, {"translation": [1, 0, 0], "children": [first + 2]},
                         {"translation": [1, 0, 0]}]
        roots.append(first)
        inverse_bind = b"".join(struct.pack("<16f", 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, -x, 0, 0, 1)
                                for x in range(3))
        doc["skins"] = [{"joints": [first, first + 1, first + 2],
                         "inverseBindMatrices": blob.add(inverse_bind, 5126, "MAT4", 3)}]
    if animate:
        times = blob.add(struct.pack("<2f", 0, 1), 5126, "SCALAR", 2, ([0], [1]))
        if animate == "bend":  # the middle joint turns 60 degrees about z
            target, path = doc["skins"][0]["joints"][1], "rotation"
            values = blob.add(struct.pack("<8f", 0, 0, 0, 1, 0, 0, 0.5, math.sqrt(0.75)), 5126, "VEC4", 2)
        else:  # a camera dollies in; nothing the skin depends on moves
            doc["cameras"] = [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1}}]
            doc["nodes"].append({"camera": 0, "translation": [1.5, 0, 6]})
            target, path = len(doc["nodes"]) - 1, "translation"
            roots.append(target)
            values = blob.add(struct.pack("<6f", 1.5, 0, 6, 1.5, 0, 5), 5126, "VEC3", 2)
        doc["animations"] = [{"samplers": [{"input": times, "output": values}],
                              "channels": [{"sampler": 0, "target": {"node": target, "path": path}}]}]
    doc["scenes"] = [{"nodes": roots}]
    while len(blob.data) % 4:
        blob.data.append(0)
    doc["buffers"] = [{"byteLength": len(blob.data)}]
    doc["bufferViews"] = blob.views
    doc["accessors"] = blob.accessors
    return doc, bytes(blob.data)


def write_glb(path, doc, binary):
    text = json.dumps(doc, separators=(",", ":")).encode()
    text += b" " * (-len(text) % 4)
    length = 12 + 8 + len(text) + 8 + len(binary)
    with open(path, "wb") as f:
        f.write(struct.pack("<4sII", b"glTF", 2, length))
        f.write(struct.pack("<I4s", len(text), b"JSON") + text)
        f.write(struct.pack("<I4s", len(binary), b"BIN\0") + binary)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("folder")
    parser.add_argument("--nodes", type=int, default=300)
    parser.add_argument("--triangles", type=int, default=180000)
    args = parser.parse_args()
    os.makedirs(args.folder, exist_ok=True)
    mesh_data = grid(args.triangles)
    cases = [("shared_skin", "shared_skin", None), ("shared_morph", "shared_morph", None),
             ("distinct_morph", "distinct_morph", None), ("animated_skin", "shared_skin", "bend"),
             ("still_skin", "shared_skin", "camera")]
    for name, kind, animate in cases:
        doc, binary = asset(mesh_data, args.nodes, kind, animate)
        write_glb(os.path.join(args.folder, name + ".glb"), doc, binary)


if __name__ == "__main__":
    main()
