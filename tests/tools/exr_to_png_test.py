#!/usr/bin/env python3
"""tools/exr_to_png.py makes the picture kiln's --preview makes from the same EXR: alpha kept
exactly, straight colour within one code (OpenImageIO's float sRGB against kiln's own curve), the
exposure applied the same way.

Usage: exr_to_png_test.py SOURCE_DIR KILN
"""

import base64
import json
import os
import struct
import subprocess
import sys
import tempfile
import unittest

import numpy as np
import OpenImageIO as oiio

SOURCE, KILN = sys.argv[1], sys.argv[2]


def triangle_gltf(path):
    """A triangle lit by kiln's headlight over an empty background: alpha 0, 1 and the edges between."""
    positions = struct.pack("9f", -1, -1, 0, 1, -1, 0, 0, 1, 0)
    uri = "data:application/octet-stream;base64," + base64.b64encode(positions).decode()
    document = {"asset": {"version": "2.0"}, "scenes": [{"nodes": [0]}], "scene": 0,
                "nodes": [{"mesh": 0}], "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
                "buffers": [{"byteLength": 36, "uri": uri}], "bufferViews": [{"buffer": 0, "byteLength": 36}],
                "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                               "min": [-1, -1, 0], "max": [1, 1, 0]}]}
    with open(path, "w") as f:
        json.dump(document, f)


def png_codes(path):
    """The PNG's stored 8-bit values, alpha not multiplied in (OpenImageIO associates it by default)."""
    config = oiio.ImageSpec()
    config.attribute("oiio:UnassociatedAlpha", 1)
    return oiio.ImageBuf(path, 0, 0, config).get_pixels(oiio.UINT8).astype(int)


class exr_to_png(unittest.TestCase):
    def test_the_png_is_kilns_preview(self):
        with tempfile.TemporaryDirectory() as folder:
            scene, exr = os.path.join(folder, "tri.gltf"), os.path.join(folder, "tri.exr")
            preview, converted = os.path.join(folder, "preview.png"), os.path.join(folder, "converted.png")
            triangle_gltf(scene)
            for stops in ("0", "1.5"):
                done = subprocess.run([KILN, "render", scene, "-o", exr, "--preview", preview, "--preview-exposure",
                                       stops, "--width", "24", "--height", "16", "--spp", "4", "--look-from",
                                       "0,0,3", "--look-at", "0,0,0", "-q"], capture_output=True, text=True)
                self.assertEqual(done.returncode, 0, done.stderr)
                done = subprocess.run([sys.executable, os.path.join(SOURCE, "tools", "exr_to_png.py"), exr,
                                       converted, "--exposure", stops], capture_output=True, text=True)
                self.assertEqual(done.returncode, 0, done.stderr)
                want, got = png_codes(preview), png_codes(converted)
                self.assertEqual(got.shape, want.shape)  # RGBA: the alpha is kept
                alpha = want[:, :, 3]
                self.assertTrue((alpha == 0).any() and (alpha == 255).any() and ((alpha > 0) & (alpha < 255)).any())
                np.testing.assert_array_equal(got[:, :, 3], alpha)
                self.assertLessEqual(np.abs(got[:, :, :3] - want[:, :, :3]).max(), 1, stops)


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1])
