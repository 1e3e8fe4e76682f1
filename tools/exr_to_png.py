#!/usr/bin/env python3
"""Convert a linear-light EXR (e.g. a kiln render) into an 8-bit sRGB PNG preview for humans.

Usage: exr_to_png.py IN.exr OUT.png [--exposure STOPS]

The same picture as kiln's `--preview`, through the same transform: NaNs become black, the colour
is scaled by 2^STOPS, clamped to [0, 1], encoded with the sRGB transfer function and quantised to
8 bits. A PNG keeps alpha, with straight colour (the premultiplied colour divided by alpha where
alpha > 0, as PNG defines it), so a viewer composites its edges over any background; a JPEG
(OUT.jpg) has no alpha and holds the premultiplied colour, the image over black. R,G,B are used
when present; a single Y (or other lone) channel is shown as grey; otherwise the first three
channels are taken. A is used when present.

Needs `oiiotool` (Debian package openimageio-tools), which does the actual work.
"""

import argparse
import os
import re
import shutil
import subprocess
import sys


def channel_names(oiiotool, path):
    """The channel names of the first subimage, from `oiiotool --info -v`."""
    out = subprocess.run([oiiotool, "--info", "-v", path], check=True,
                         capture_output=True, text=True).stdout
    m = re.search(r"channel list:\s*(.*)", out)
    if not m:
        raise RuntimeError("could not read the channel list of %s" % path)
    # Mixed-format files list each channel with its type, e.g. "R (half), Z (float)".
    names = [re.sub(r"\s*\(.*\)$", "", c.strip()) for c in m.group(1).split(",")]
    return [n for n in names if n]


def rgb_selection(names):
    """An oiiotool --ch argument giving three channels to show."""
    if all(c in names for c in ("R", "G", "B")):
        return "R,G,B"
    if "Y" in names:
        return "R=Y,G=Y,B=Y"
    if len(names) >= 3:
        return "R=%s,G=%s,B=%s" % tuple(names[:3])
    return "R=%s,G=%s,B=%s" % ((names[0],) * 3)


def build_command(oiiotool, src, dst, exposure, channels, alpha):
    """The oiiotool command line; alpha: the file has an A channel and dst keeps it (a PNG)."""
    scale = repr(2.0 ** exposure)
    if not alpha:
        return [oiiotool, src, "--ch", channels, "--fixnan", "black", "--mulc", scale,
                "--clamp:min=0:max=1", "--colorconvert", "linear", "sRGB", "-d", "uint8", "-o", dst]
    # Straight colour as kiln's preview writes it: divided by alpha before the curve, and the file
    # marked as holding unassociated alpha so that the PNG writer does not divide it again.
    return [oiiotool, src, "--ch", channels + ",A", "--fixnan", "black", "--unpremult",
            "--mulc", ",".join([scale] * 3 + ["1"]), "--clamp:min=0:max=1",
            "--colorconvert:unpremult=0", "linear", "sRGB",
            "--attrib:type=int", "oiio:UnassociatedAlpha", "1", "-d", "uint8", "-o", dst]


def main(argv=None):
    parser = argparse.ArgumentParser(
        description="Convert a linear EXR to an 8-bit sRGB PNG preview, as kiln's --preview writes it "
                    "(uses oiiotool).")
    parser.add_argument("input", metavar="IN.exr")
    parser.add_argument("output", metavar="OUT.png")
    parser.add_argument("--exposure", type=float, default=0.0, metavar="STOPS",
                        help="scale the linear values by 2^STOPS before encoding (default 0)")
    parser.add_argument("--verbose", "-v", action="store_true",
                        help="print the oiiotool command line")
    args = parser.parse_args(argv)

    oiiotool = shutil.which("oiiotool")
    if not oiiotool:
        print("exr_to_png.py: oiiotool not found (install openimageio-tools)", file=sys.stderr)
        return 2
    if not os.path.isfile(args.input):
        print("exr_to_png.py: no such file: %s" % args.input, file=sys.stderr)
        return 2

    try:
        names = channel_names(oiiotool, args.input)
        keeps_alpha = "A" in names and not args.output.lower().endswith((".jpg", ".jpeg"))
        cmd = build_command(oiiotool, args.input, args.output, args.exposure,
                            rgb_selection(names), keeps_alpha)
        if args.verbose:
            print(" ".join(cmd))
        subprocess.run(cmd, check=True, capture_output=not args.verbose, text=True)
    except subprocess.CalledProcessError as e:
        detail = (e.stderr or e.stdout or "").strip()
        print("exr_to_png.py: oiiotool failed (exit %d)%s" % (
            e.returncode, ": " + detail if detail else ""), file=sys.stderr)
        return 1
    except RuntimeError as e:
        print("exr_to_png.py: %s" % e, file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
