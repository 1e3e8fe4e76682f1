#!/usr/bin/python3
"""Writes the assets that measure kiln's memory at its documented limits into a folder:

  big_texture.gltf   a quad textured by a 16384x16384 PNG (2^28 texels, the --max-texels limit;
                     one solid colour, a few MB on disk) through a mip-mapped sampler
  shared_100.gltf    one mesh of 100 primitives that all use one 100k-triangle accessor set
  shared_1.gltf      the same mesh with one primitive, the baseline
  json_MB.gltf       a small triangle padded with MB megabytes of JSON (asset extras), for each
                     size given with --json-mb
  huge.gltf          a sparse 2.2 GB file (made with truncate: no disk used)

Measure with /usr/bin/time -v build/renderer/app/kiln render FILE -o out.exr (max RSS).
"""
import argparse
import base64
import json
import os
import struct
import zlib


def png_solid(width, height, rgb):
    """A solid-colour 8-bit RGB PNG, compressed row by row so the writer stays small."""
    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body) & 0xFFFFFFFF)

    row = b"\x00" + bytes(rgb) * width  # filter byte 0, then the texels
    compressor = zlib.compressobj(9)
    parts = [compressor.compress(row) for _ in range(height)]
    parts.append(compressor.flush())
    header = struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", b"".join(parts)) +
            chunk(b"IEND", b""))


def data_uri(data):
    return "data:application/octet-stream;base64," + base64.b64encode(data).decode()


def quad_gltf(extra_material=None):
    """A unit quad in front of the default camera, with UVs."""
    positions = struct.pack("<12f", -1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0)
    uvs = struct.pack("<8f", 0, 1, 1, 1, 1, 0, 0, 0)
    indices = struct.pack("<6H", 0, 1, 2, 0, 2, 3)
    blob = positions + uvs + indices
    doc = {
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "indices": 2,
                                    "material": 0}]}],
        "materials": [extra_material or {"pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.8, 0.8, 1]}}],
        "buffers": [{"byteLength": len(blob), "uri": data_uri(blob)}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48},
                        {"buffer": 0, "byteOffset": 48, "byteLength": 32},
                        {"buffer": 0, "byteOffset": 80, "byteLength": 12}],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [-1, -1, 0], "max": [1, 1, 0]},
            {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC2"},
            {"bufferView": 2, "componentType": 5123, "count": 6, "type": "SCALAR"},
        ],
    }
    return doc


def big_texture(folder, side):
    with open(os.path.join(folder, "big_texture.png"), "wb") as f:
        f.write(png_solid(side, side, (200, 120, 40)))
    doc = quad_gltf({"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}})
    doc["textures"] = [{"source": 0, "sampler": 0}]
    doc["images"] = [{"uri": "big_texture.png"}]
    doc["samplers"] = [{"magFilter": 9729, "minFilter": 9987}]  # LINEAR_MIPMAP_LINEAR
    with open(os.path.join(folder, "big_texture.gltf"), "w") as f:
        json.dump(doc, f)


def grid_mesh(triangles):
    """A flat grid of about `triangles` triangles: float positions and uint32 indices."""
    n = max(1, int((triangles / 2) ** 0.5))
    positions = bytearray()
    for j in range(n + 1):
        for i in range(n + 1):
            positions += struct.pack("<3f", -1 + 2 * i / n, -1 + 2 * j / n, 0)
    indices = bytearray()
    for j in range(n):
        for i in range(n):
            a = j * (n + 1) + i
            indices += struct.pack("<6I", a, a + 1, a + n + 2, a, a + n + 2, a + n + 1)
    return bytes(positions), bytes(indices), (n + 1) * (n + 1), 6 * n * n


def shared_accessor(folder, primitives, triangles, name):
    positions, indices, vertices, index_count = grid_mesh(triangles)
    bin_name = "shared_grid.bin"
    with open(os.path.join(folder, bin_name), "wb") as f:
        f.write(positions + indices)
    doc = {
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "material": p % 2}
                                   for p in range(primitives)]}],
        "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.2, 0.2, 1]}},
                      {"pbrMetallicRoughness": {"baseColorFactor": [0.2, 0.8, 0.2, 1]}}],
        "buffers": [{"byteLength": len(positions) + len(indices), "uri": bin_name}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": len(positions)},
                        {"buffer": 0, "byteOffset": len(positions), "byteLength": len(indices)}],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": vertices, "type": "VEC3",
             "min": [-1, -1, 0], "max": [1, 1, 0]},
            {"bufferView": 1, "componentType": 5125, "count": index_count, "type": "SCALAR"},
        ],
    }
    with open(os.path.join(folder, name), "w") as f:
        json.dump(doc, f)


def padded_json(folder, megabytes):
    doc = quad_gltf()
    entry = {"k": 1}
    count = megabytes * (1 << 20) // (len(json.dumps(entry, separators=(",", ":"))) + 1)
    doc["asset"]["extras"] = {"padding": [entry] * count}
    with open(os.path.join(folder, "json_%d.gltf" % megabytes), "w") as f:
        json.dump(doc, f, separators=(",", ":"))


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("folder")
    parser.add_argument("--texture-side", type=int, default=16384)
    parser.add_argument("--triangles", type=int, default=100000)
    parser.add_argument("--json-mb", type=int, nargs="*", default=[10, 50])
    args = parser.parse_args()
    os.makedirs(args.folder, exist_ok=True)
    big_texture(args.folder, args.texture_side)
    shared_accessor(args.folder, 100, args.triangles, "shared_100.gltf")
    shared_accessor(args.folder, 1, args.triangles, "shared_1.gltf")
    for mb in args.json_mb:
        padded_json(args.folder, mb)
    with open(os.path.join(args.folder, "huge.gltf"), "wb") as f:
        f.truncate(2200 * 1000 * 1000)


if __name__ == "__main__":
    main()
