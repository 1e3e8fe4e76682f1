#!/usr/bin/env python3
"""Put a kiln render beside a reference screenshot, both at one height, in one sRGB PNG.

Usage: beside_screenshot.py RENDER.exr SCREENSHOT OUT.png [--height PIXELS] [--exposure STOPS]

The render (linear light) is scaled by 2^STOPS, clamped and sRGB-encoded as exr_to_png.py does;
the screenshot (already display-referred: JPEG or PNG) is only resized. Left: kiln, right: the
reference. Needs `oiiotool` (Debian package openimageio-tools).
"""

import argparse
import shutil
import subprocess
import sys


def main(argv=None):
    parser = argparse.ArgumentParser(description="kiln render beside a reference screenshot")
    parser.add_argument("render")
    parser.add_argument("screenshot")
    parser.add_argument("out")
    parser.add_argument("--height", type=int, default=360)
    parser.add_argument("--exposure", type=float, default=0.0)
    args = parser.parse_args(argv)
    oiiotool = shutil.which("oiiotool")
    if not oiiotool:
        sys.exit("beside_screenshot.py: oiiotool not found (apt install openimageio-tools)")
    size = "0x%d" % args.height
    command = [
        oiiotool,
        args.render, "--ch", "R,G,B", "--fixnan", "black", "--mulc", repr(2.0 ** args.exposure),
        "--clamp:min=0", "--colorconvert", "linear", "sRGB", "--resize", size,
        "-i", args.screenshot, "--ch", "R,G,B", "--resize", size,
        "--mosaic:pad=8", "2x1",
        "-d", "uint8", "-o", args.out,
    ]
    subprocess.run(command, check=True)


if __name__ == "__main__":
    main()
