#!/usr/bin/env python3
"""Writes the broken glTF files of tests/data/bad_gltf/ for the CLI's bad-input test.

Each file is one small, valid triangle scene with exactly one defect, so that a failure to
refuse it points at one check. Standard library only; the output is deterministic, so running
it again must leave `git status` clean.

    python3 tools/make_bad_gltf.py [output-folder]   (default: tests/data/bad_gltf)
"""

import base64
import json
import os
import struct
import sys
import zlib

FLOAT, USHORT = 5126, 5123


def triangle_buffer():
    """Three float positions and three u16 indices (padded to 4 bytes): 36 + 8 bytes."""
    positions = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0)
    indices = struct.pack("<3H", 0, 1, 2) + b"\0\0"
    return positions + indices


def triangle_doc(buffer_uri, index_values=(0, 1, 2)):
    """A one-triangle glTF document; `index_values` go into the buffer the URI names."""
    doc = {
        "asset": {"version": "2.0", "generator": "kiln tools/make_bad_gltf.py"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
        "accessors": [
            {"bufferView": 0, "componentType": FLOAT, "count": 3, "type": "VEC3",
             "min": [0, 0, 0], "max": [1, 1, 0]},
            {"bufferView": 1, "componentType": USHORT, "count": 3, "type": "SCALAR"},
        ],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": 36},
            {"buffer": 0, "byteOffset": 36, "byteLength": 6},
        ],
        "buffers": [{"byteLength": 44}],
    }
    if buffer_uri is not None:
        doc["buffers"][0]["uri"] = buffer_uri
    return doc


def data_uri(data):
    return "data:application/octet-stream;base64," + base64.b64encode(data).decode("ascii")


def buffer_with_indices(values):
    positions = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0)
    return positions + struct.pack("<3H", *values) + b"\0\0"


def glb(doc, binary):
    text = json.dumps(doc, separators=(",", ":")).encode("utf-8")
    text += b" " * (-len(text) % 4)
    binary += b"\0" * (-len(binary) % 4)
    total = 12 + 8 + len(text) + 8 + len(binary)
    return (struct.pack("<4sII", b"glTF", 2, total) + struct.pack("<I4s", len(text), b"JSON") + text +
            struct.pack("<I4s", len(binary), b"BIN\0") + binary)


def write(folder, name, content):
    path = os.path.join(folder, name)
    mode = "wb" if isinstance(content, bytes) else "w"
    with open(path, mode) as out:
        out.write(content)


def dumps(doc):
    # allow_nan stays True on purpose: Python writes NaN as a bare `NaN` token, the way real
    # exporters produce broken files.
    return json.dumps(doc, indent=2) + "\n"


def main():
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    folder = sys.argv[1] if len(sys.argv) > 1 else os.path.join(root, "tests", "data", "bad_gltf")
    os.makedirs(folder, exist_ok=True)

    # The whole GLB minus its last 12 bytes: the header still declares the full length.
    whole = glb(triangle_doc(None), triangle_buffer())
    write(folder, "truncated.glb", whole[:-12])

    # Index 7 into a mesh of 3 vertices.
    write(folder, "out_of_range_index.gltf", dumps(triangle_doc(data_uri(buffer_with_indices((0, 1, 7))))))

    # POSITION claims 4 vertices (48 bytes) in a 36-byte bufferView that ends the positions.
    doc = triangle_doc(data_uri(triangle_buffer()))
    doc["accessors"][0]["count"] = 4
    write(folder, "accessor_past_buffer_end.gltf", dumps(doc))

    # The buffer lives in missing.bin, which is deliberately not written.
    write(folder, "missing_bin.gltf", dumps(triangle_doc("missing.bin")))

    doc = triangle_doc(data_uri(triangle_buffer()))
    doc["extensionsUsed"] = ["KHR_texture_basisu"]
    doc["extensionsRequired"] = ["KHR_texture_basisu"]
    write(folder, "unsupported_required_extension.gltf", dumps(doc))

    doc = triangle_doc(data_uri(triangle_buffer()))
    doc["nodes"][0]["matrix"] = [1, 0, 0, 0, 0, float("nan"), 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]
    write(folder, "nan_matrix.gltf", dumps(doc))

    write(folder, "not_json.gltf", "this is not JSON: {\"asset\": \n")

    # A textured triangle whose PNG ends inside its IDAT chunk.
    doc = triangle_doc(data_uri(triangle_buffer()))
    doc["materials"] = [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}]
    doc["meshes"][0]["primitives"][0]["material"] = 0
    doc["textures"] = [{"source": 0}]
    doc["images"] = [{"uri": "truncated_png.png"}]
    write(folder, "truncated_png.gltf", dumps(doc))
    write(folder, "truncated_png.png", checker_png()[:-30])

    # A buffer URI that climbs out of the asset's folder towards a system file.
    write(folder, "escapes_folder.gltf", dumps(triangle_doc("../../../../../../etc/passwd")))


def checker_png(size=16):
    """A small opaque RGB checkerboard PNG, built with the standard library."""
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))
    rows = b"".join(b"\0" + b"".join(b"\xff\x80\x00" if (x // 4 + y // 4) % 2 else b"\x10\x10\x60"
                                       for x in range(size)) for y in range(size))
    header = struct.pack(">IIBBBBB", size, size, 8, 2, 0, 0, 0)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(rows))
            + chunk(b"IEND", b""))


if __name__ == "__main__":
    main()
