#!/usr/bin/env python3
"""Writes kiln's studio environment, share/environments/studio.exr: the neutral light an asset
without lights is shown under by default (`kiln render --lighting auto`).

A grey studio in glTF's frame (+Y up; the default camera looks from +Z toward -Z): a soft dome
brighter overhead than at the horizon, a darker floor, and three soft box lights: a key above and to
the camera's left, a weaker fill to its right, and a rim light behind. The map is an equirectangular
OpenEXR image (RGB half, ZIP compression), written with the standard library alone so that the file
is reproducible byte for byte: `python3 tools/make_studio_environment.py --check` fails when the
shipped file differs from what this script writes.
"""
import argparse
import math
import os
import struct
import sys
import zlib

WIDTH, HEIGHT = 512, 256
ROWS_PER_BLOCK = 16  # OpenEXR's ZIP compression works on blocks of 16 scanlines

# Soft box lights: (direction toward the light, half-angle in degrees, RGB radiance).
KEY = ((-0.55, 0.62, 0.56), 16.0, (9.0, 8.7, 8.2))
FILL = ((0.75, 0.25, 0.6), 22.0, (2.0, 2.05, 2.15))
RIM = ((0.2, 0.55, -0.8), 12.0, (6.0, 6.0, 6.2))


def normalized(v):
    n = math.sqrt(sum(c * c for c in v))
    return tuple(c / n for c in v)


def direction(u, v):
    """kiln's equirectangular mapping (shade/environment.h) for a map without rotation."""
    phi = (u - 0.5) * 2.0 * math.pi
    theta = v * math.pi
    return (math.sin(theta) * math.sin(phi), math.cos(theta), -math.sin(theta) * math.cos(phi))


def smoothstep(edge0, edge1, x):
    t = min(max((x - edge0) / (edge1 - edge0), 0.0), 1.0)
    return t * t * (3.0 - 2.0 * t)


def box_light(d, light):
    """A soft disk light: full radiance inside its half-angle, fading out over a quarter of it."""
    axis, half_angle, rgb = light
    cos_angle = sum(a * b for a, b in zip(normalized(axis), d))
    angle = math.degrees(math.acos(max(-1.0, min(1.0, cos_angle))))
    weight = 1.0 - smoothstep(half_angle * 0.75, half_angle * 1.25, angle)
    return tuple(c * weight for c in rgb)


def radiance(d):
    y = d[1]
    if y >= 0.0:
        # Dome: 0.55 at the horizon rising to 0.9 overhead, slightly cool.
        level = 0.55 + 0.35 * math.sqrt(y)
        base = (level * 0.97, level * 0.99, level * 1.03)
    else:
        # Floor: a dark warm grey, darker straight down; a soft seam at the horizon.
        level = 0.12 + 0.43 * smoothstep(-0.15, 0.0, y) - 0.04 * smoothstep(-1.0, -0.3, y) * -y
        base = (level * 1.02, level, level * 0.97)
    lights = [box_light(d, light) for light in (KEY, FILL, RIM)]
    return tuple(base[c] + sum(l[c] for l in lights) for c in range(3))


def half_bytes(value):
    return struct.pack("<e", value)


def scanline(y):
    """One scanline in EXR order: each channel (B, G, R, alphabetical) for the whole row."""
    v = (y + 0.5) / HEIGHT
    row = [radiance(direction((x + 0.5) / WIDTH, v)) for x in range(WIDTH)]
    return b"".join(b"".join(half_bytes(p[c]) for p in row) for c in (2, 1, 0))


def zip_block(raw):
    """OpenEXR's ZIP compression: bytes split into even and odd halves, delta-coded, deflated."""
    reordered = raw[0::2] + raw[1::2]
    predicted = bytearray(reordered)
    for i in range(len(predicted) - 1, 0, -1):
        predicted[i] = (reordered[i] - reordered[i - 1] + 128) & 0xFF
    packed = zlib.compress(bytes(predicted), 9)
    return packed if len(packed) < len(raw) else raw


def attribute(name, kind, payload):
    return name.encode() + b"\0" + kind.encode() + b"\0" + struct.pack("<i", len(payload)) + payload


def header():
    channels = b"".join(c.encode() + b"\0" + struct.pack("<iB3xii", 1, 0, 1, 1) for c in "BGR") + b"\0"
    window = struct.pack("<iiii", 0, 0, WIDTH - 1, HEIGHT - 1)
    return (
        struct.pack("<ii", 20000630, 2)
        + attribute("channels", "chlist", channels)
        + attribute("compression", "compression", bytes([3]))  # ZIP_COMPRESSION
        + attribute("dataWindow", "box2i", window)
        + attribute("displayWindow", "box2i", window)
        + attribute("lineOrder", "lineOrder", bytes([0]))
        + attribute("pixelAspectRatio", "float", struct.pack("<f", 1.0))
        + attribute("screenWindowCenter", "v2f", struct.pack("<ff", 0.0, 0.0))
        + attribute("screenWindowWidth", "float", struct.pack("<f", 1.0))
        + b"\0"
    )


def exr_bytes():
    head = header()
    blocks = []
    for y0 in range(0, HEIGHT, ROWS_PER_BLOCK):
        raw = b"".join(scanline(y) for y in range(y0, min(y0 + ROWS_PER_BLOCK, HEIGHT)))
        data = zip_block(raw)
        blocks.append(struct.pack("<ii", y0, len(data)) + data)
    offset = len(head) + 8 * len(blocks)
    table = b""
    for block in blocks:
        table += struct.pack("<Q", offset)
        offset += len(block)
    return head + table + b"".join(blocks)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    here = os.path.dirname(os.path.abspath(__file__))
    parser.add_argument("--output", default=os.path.join(here, "..", "share", "environments", "studio.exr"))
    parser.add_argument("--check", action="store_true", help="compare with the file instead of writing it")
    args = parser.parse_args()
    data = exr_bytes()
    if args.check:
        with open(args.output, "rb") as f:
            same = f.read() == data
        print(("matches " if same else "DIFFERS from ") + args.output)
        return 0 if same else 1
    with open(args.output, "wb") as f:
        f.write(data)
    print("wrote", args.output, len(data), "bytes")
    return 0


if __name__ == "__main__":
    sys.exit(main())
