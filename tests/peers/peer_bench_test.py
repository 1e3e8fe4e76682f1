#!/usr/bin/env python3
"""Checks for the peer benchmark's inputs and parsers (bench/peers, tools/make_peer_quadric_scene.py).
No renderer is timed here: this tests that both renderers get the same scene and that the
benchmark reads their outputs right.

Usage: peer_bench_test.py SOURCE_DIR KILN
"""

import json
import os
import subprocess
import sys
import tempfile
import unittest

SOURCE, KILN = sys.argv[1], sys.argv[2]
sys.path.insert(0, os.path.join(SOURCE, "tools"))
sys.path.insert(0, os.path.join(SOURCE, "bench", "peers"))
import make_peer_quadric_scene as gen  # noqa: E402
import peer_bench  # noqa: E402

CYCLES_LOG = """\
Fra:1 Mem:9.1M (Peak 9.1M) | Time:00:00.15 | Mem:0.00M, Peak:0.00M | Scene, ViewLayer | Synchronizing object | Glass
Fra:1 Mem:9.1M (Peak 9.1M) | Time:00:00.78 | Mem:1.0M, Peak:1.0M | Scene, ViewLayer | Updating Scene BVH | Building BVH
Fra:1 Mem:9.1M (Peak 9.1M) | Time:00:00.84 | Mem:1.0M, Peak:1.0M | Scene, ViewLayer | Updating Scene BVH | Copying BVH to device
Fra:1 Mem:9.1M (Peak 9.1M) | Time:00:00.86 | Mem:1.0M, Peak:1.0M | Scene, ViewLayer | Updating Mesh | Computing normals
Fra:1 Mem:9.1M (Peak 9.1M) | Time:00:00.90 | Mem:1.0M, Peak:1.0M | Scene, ViewLayer | Sample 0/16
Fra:1 Mem:9.1M (Peak 9.1M) | Time:00:01.15 | Remaining:00:04.42 | Mem:1.0M, Peak:1.0M | Scene, ViewLayer | Sample 1/16
Fra:1 Mem:9.1M (Peak 9.1M) | Time:00:04.75 | Mem:1.0M, Peak:1.0M | Scene, ViewLayer | Finished
"""


class GeneratedScene(unittest.TestCase):
    def test_committed_files_are_what_the_generator_writes(self):
        # The glTF and the POV-Ray file are only the same scene while both come from one run.
        with tempfile.TemporaryDirectory() as tmp:
            gltf, pov = os.path.join(tmp, "q.gltf"), os.path.join(tmp, "q.pov")
            subprocess.run([sys.executable, os.path.join(SOURCE, "tools", "make_peer_quadric_scene.py"),
                            "--gltf", gltf, "--pov", pov], check=True, capture_output=True)
            for new, old in ((gltf, "scenes/peer_quadrics.gltf"), (pov, "bench/peers/peer_quadrics.pov")):
                with open(new, "rb") as a, open(os.path.join(SOURCE, old), "rb") as b:
                    self.assertEqual(a.read(), b.read(), old + " is stale: rerun tools/make_peer_quadric_scene.py")

    def test_kiln_renders_the_scene_with_its_two_lights(self):
        with tempfile.TemporaryDirectory() as tmp:
            p = subprocess.run([KILN, "render", os.path.join(SOURCE, "scenes", "peer_quadrics.gltf"), "-o",
                                os.path.join(tmp, "q.exr"), "--width", "32", "--height", "24", "--threads", "1",
                                "--spp", "1"],
                               capture_output=True, text=True)
            self.assertEqual(p.returncode, 0, p.stderr)
            m = peer_bench.KILN_SUMMARY.search(p.stderr + p.stdout)
            self.assertIsNotNone(m, p.stderr)
            self.assertEqual(int(m.group(4)), 32 * 24)  # camera rays, 1 spp
            self.assertGreater(int(m.group(5)), 32 * 24)  # shadow rays: two lights, most pixels hit
            self.assertGreater(int(m.group(6)), 0)  # the mirror sphere is in view
            self.assertGreater(int(m.group(7)), 0)  # and the glass sphere

    def test_pov_matrix_places_object_points_where_gltf_does_with_z_negated(self):
        linear = gen.matmul(gen.rot_y(-25), gen.matmul(gen.rot_x(-60), gen.UP_X))
        t = (4.2, 0.75, -2.2)
        nums = [float(x) for x in gen.pov_matrix(linear, t)[len("matrix <"):-1].split(",")]
        rows = [nums[0:3], nums[3:6], nums[6:9], nums[9:12]]
        for p in ((1, 0, 0), (0, 2, 0), (0.3, -0.5, 1.5)):
            world = [sum(linear[r][c] * p[c] for c in range(3)) + t[r] for r in range(3)]
            pov = [sum(p[i] * rows[i][c] for i in range(3)) + rows[3][c] for c in range(3)]  # row vector
            for a, b in zip(pov, (world[0], world[1], -world[2])):
                self.assertAlmostEqual(a, b, places=5)

    def test_upright_turns_object_z_to_world_y(self):
        self.assertEqual([gen.UP_X[r][2] for r in range(3)], [0, 1, 0])

    def test_pov_light_falls_off_as_the_inverse_square_of_kiln(self):
        # POV-Ray: colour * 2 / (1 + (d / fade)^2); kiln's diffuse: I/pi / d^2 (the BRDF's 1/pi).
        name, _, colour, intensity = gen.LIGHTS[0]
        scale = intensity / 3.141592653589793 / (2 * gen.FADE_DISTANCE ** 2)
        for d in (1.0, 5.0, 12.0):
            pov = scale * 2 / (1 + (d / gen.FADE_DISTANCE) ** 2)
            self.assertAlmostEqual(pov / (intensity / 3.141592653589793 / d ** 2), 1.0, places=5)


class Parsers(unittest.TestCase):
    def test_cycles_phases_from_its_own_clock(self):
        p = peer_bench.cycles_phases(CYCLES_LOG)
        self.assertAlmostEqual(p["sync_s"], 0.78)
        self.assertAlmostEqual(p["bvh_s"], 0.08)
        self.assertAlmostEqual(p["sampling_s"], 3.85)
        self.assertAlmostEqual(p["cycles_s"], 4.75)

    def test_toycar_wrapper_keeps_one_camera_and_adds_one_light(self):
        asset = peer_bench.find_toycar(os.path.join(SOURCE, "..", "shared", "assets"))
        if not asset:
            self.skipTest("ToyCar not in ../shared/assets")
        with tempfile.TemporaryDirectory() as tmp:
            path = peer_bench.toycar_wrapper(asset, tmp, 640, 480)
            with open(path, encoding="utf-8") as f:
                g = json.load(f)
            nodes = [g["nodes"][i] for i in g["scenes"][0]["nodes"]]
            cams = [n for n in nodes if "camera" in n]
            self.assertEqual([c["name"] for c in cams], ["Camera001"])
            self.assertEqual(len(g["cameras"]), 1)
            self.assertAlmostEqual(g["cameras"][0]["perspective"]["aspectRatio"], 640 / 480)
            self.assertEqual(len(g["extensions"]["KHR_lights_punctual"]["lights"]), 1)
            for item in g["buffers"] + g["images"]:
                self.assertTrue(os.path.isfile(os.path.join(tmp, item["uri"])), item["uri"])


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1])
