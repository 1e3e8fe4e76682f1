#!/usr/bin/env python3
"""Writes a small procedural equirectangular sky (Radiance .hdr, flat RGBE scanlines) for kiln's
--environment option: a blue gradient sky with a bright sun, and a chequered ground below the
horizon so that reflections and refractions show where they look. Pure Python, no dependencies.

usage: make_environment_map.py OUT.hdr [--width 256]
"""
import argparse
import math


def rgbe(r, g, b):
    """Radiance's shared-exponent encoding of one linear RGB value."""
    m = max(r, g, b)
    if m < 1e-32:
        return bytes((0, 0, 0, 0))
    mantissa, exponent = math.frexp(m)
    scale = mantissa * 256.0 / m
    return bytes((int(r * scale), int(g * scale), int(b * scale), exponent + 128))


def sky(u, v):
    """Radiance at equirectangular (u, v): v = 0 straight up, 0.5 the horizon."""
    if v < 0.5:
        # Sun at u = 0.6, 30 degrees above the horizon (v = 1/3), about 4 degrees across.
        du, dv = (u - 0.6) * 2.0 * math.pi * math.sin(v * math.pi), (v - 1.0 / 3.0) * math.pi
        if du * du + dv * dv < 0.035 ** 2:
            return (60.0, 55.0, 45.0)
        t = v * 2.0
        return (0.25 + 0.5 * t, 0.45 + 0.35 * t, 1.0)
    check = (int(u * 32) + int(v * 16)) % 2
    shade = 0.35 if check else 0.1
    return (shade, shade * 0.9, shade * 0.8)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("out", help="the Radiance .hdr file to write")
    parser.add_argument("--width", type=int, default=256,
                        help="width in pixels; the height is half of it (default 256)")
    args = parser.parse_args()
    width, height = args.width, args.width // 2
    with open(args.out, "wb") as f:
        f.write(b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n")
        f.write(f"-Y {height} +X {width}\n".encode())
        for y in range(height):
            f.write(b"".join(rgbe(*sky((x + 0.5) / width, (y + 0.5) / height)) for x in range(width)))


if __name__ == "__main__":
    main()
