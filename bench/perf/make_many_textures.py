#!/usr/bin/python3
"""Writes a scene of many textured quads, each with its own base colour PNG, for timing how long
a render takes to load and decode a scene's images (docs/performance.md, "Many textures").

Usage: make_many_textures.py OUT_DIR [--count 100] [--size 1024]
Writes OUT_DIR/many_textures.gltf, its .bin and tex_NNN.png: a grid of count quads, each image
size x size RGB, 8-bit, a pattern of its own with low-amplitude noise (so each compresses like a
photographed texture, not like a flat colour). Needs python3-numpy.
"""

import argparse
import json
import math
import os
import struct
import zlib

import numpy as np


def png_bytes(rgb):
    """An 8-bit RGB PNG of the array rgb (height x width x 3, uint8), filter 0 on every row."""
    height, width, _ = rgb.shape
    raw = np.concatenate([np.zeros((height, 1), np.uint8), rgb.reshape(height, width * 3)], axis=1)

    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body) & 0xFFFFFFFF)

    header = struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(raw.tobytes(), 6))
            + chunk(b"IEND", b""))


def texture(index, size, rng):
    y, x = np.mgrid[0:size, 0:size].astype(np.float32) / size
    f = 2.0 + index % 7
    r = 0.5 + 0.5 * np.sin(2 * math.pi * f * x + index)
    g = 0.5 + 0.5 * np.sin(2 * math.pi * (f + 1) * y)
    b = ((np.floor(x * (index % 5 + 2)) + np.floor(y * (index % 3 + 2))) % 2).astype(np.float32)
    rgb = np.stack([r, g, 0.3 + 0.4 * b], axis=-1) * 230 + rng.integers(0, 24, (size, size, 3))
    return np.clip(rgb, 0, 255).astype(np.uint8)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("out_dir")
    parser.add_argument("--count", type=int, default=100)
    parser.add_argument("--size", type=int, default=1024)
    args = parser.parse_args()
    os.makedirs(args.out_dir, exist_ok=True)
    rng = np.random.default_rng(1)
    for i in range(args.count):
        with open(os.path.join(args.out_dir, "tex_%03d.png" % i), "wb") as f:
            f.write(png_bytes(texture(i, args.size, rng)))

    # One unit quad in the XY plane, shared by every mesh; each mesh has its own material.
    positions = struct.pack("<12f", 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0)
    uvs = struct.pack("<8f", 0, 1, 1, 1, 1, 0, 0, 0)
    indices = struct.pack("<6H", 0, 1, 2, 0, 2, 3)
    binary = positions + uvs + indices
    with open(os.path.join(args.out_dir, "many_textures.bin"), "wb") as f:
        f.write(binary)
    side = math.ceil(math.sqrt(args.count))
    doc = {
        "asset": {"version": "2.0", "generator": "bench/perf/make_many_textures.py"},
        "buffers": [{"uri": "many_textures.bin", "byteLength": len(binary)}],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": 48},
            {"buffer": 0, "byteOffset": 48, "byteLength": 32},
            {"buffer": 0, "byteOffset": 80, "byteLength": 12},
        ],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
            {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC2"},
            {"bufferView": 2, "componentType": 5123, "count": 6, "type": "SCALAR"},
        ],
        "images": [{"uri": "tex_%03d.png" % i} for i in range(args.count)],
        "textures": [{"source": i} for i in range(args.count)],
        "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": i}, "metallicFactor": 0}}
                      for i in range(args.count)],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "indices": 2, "material": i}]}
                   for i in range(args.count)],
        "nodes": [{"mesh": i, "translation": [1.1 * (i % side), 1.1 * (i // side), 0]} for i in range(args.count)],
        "scenes": [{"nodes": list(range(args.count))}],
        "scene": 0,
    }
    with open(os.path.join(args.out_dir, "many_textures.gltf"), "w") as f:
        json.dump(doc, f)
    print("wrote %d textures of %dx%d to %s" % (args.count, args.size, args.size, args.out_dir))


if __name__ == "__main__":
    main()
