#!/usr/bin/env python3
"""Generate scenes/quadric_showcase.gltf: every KILN_quadric kind in one scene (docs/quadrics.md).

World is glTF's: metres, +Y up. Quadrics have their axis along object +Z, so upright ones are
placed with a -90 degree rotation about X (object +Z -> world +Y).

  ground      a disk of radius 12 (kind "disk"), grey
  back row    capped cylinder, capped cone, capped paraboloid, hyperboloid of one sheet,
              hyperboloid of two sheets (capped), left to right
  front row   solid glass sphere (KHR_materials_transmission + KHR_materials_ior + KHR_materials_volume:
              without a volume glTF treats a transmissive surface as a thin wall), mirror torus
              (metallic 1, roughness 0), a general quadric (a saddle z = x^2 - y^2 clipped to a
              box), and an ellipsoid: the shared sphere definition under a non-uniform scale
  annulus     an upright disk with a hole (inner_radius), mirrored by a negative scale

The sphere definition is placed by two nodes (one Embree user-geometry scene, two instances).
Python 3 standard library only; the output is deterministic JSON.

Usage: python3 tools/make_quadric_showcase.py [--out scenes/quadric_showcase.gltf]
"""

import argparse
import json
import math
import os

UPRIGHT = [-math.sqrt(0.5), 0.0, 0.0, math.sqrt(0.5)]  # quaternion: -90 degrees about X


def quat_axis_angle(axis, degrees):
    n = math.sqrt(sum(a * a for a in axis))
    h = math.radians(degrees) / 2
    return [axis[0] / n * math.sin(h), axis[1] / n * math.sin(h), axis[2] / n * math.sin(h), math.cos(h)]


def quat_mul(a, b):
    ax, ay, az, aw = a
    bx, by, bz, bw = b
    return [aw * bx + ax * bw + ay * bz - az * by, aw * by - ax * bz + ay * bw + az * bx,
            aw * bz + ax * by - ay * bx + az * bw, aw * bw - ax * bx - ay * by - az * bz]


def tidy(values):
    return [round(v, 7) + 0.0 for v in values]


def material(name, color, metallic=0.0, roughness=0.5, extensions=None):
    m = {"name": name,
         "pbrMetallicRoughness": {"baseColorFactor": tidy(list(color) + [1.0]), "metallicFactor": metallic,
                                  "roughnessFactor": roughness}}
    if extensions:
        m["extensions"] = extensions
    return m


def build():
    primitives = [
        {"name": "ground", "kind": "disk", "radius": 12.0},
        {"name": "cylinder", "kind": "cylinder", "radius": 0.6, "zmin": 0.0, "zmax": 1.6, "caps": True},
        {"name": "cone", "kind": "cone", "radius": 0.8, "height": 1.8, "caps": True},
        {"name": "paraboloid", "kind": "paraboloid", "radius": 0.8, "zmin": 0.0, "zmax": 1.6, "caps": True},
        {"name": "hyperboloid1", "kind": "hyperboloid_one_sheet", "radius": 0.35, "c": 0.45, "zmin": -0.8,
         "zmax": 0.8, "caps": False},
        {"name": "hyperboloid2", "kind": "hyperboloid_two_sheets", "radius": 0.3, "c": 0.3, "zmin": -0.9,
         "zmax": 0.9, "caps": True},
        {"name": "sphere", "kind": "sphere", "radius": 1.0},
        {"name": "torus", "kind": "torus", "major_radius": 0.75, "minor_radius": 0.25},
        # Saddle z = x^2 - y^2: x^2 - y^2 - z = 0, clipped to a box.
        {"name": "saddle", "kind": "general", "coefficients": [1, -1, 0, 0, 0, 0, 0, 0, -1, 0],
         "box_min": [-0.8, -0.8, -0.8], "box_max": [0.8, 0.8, 0.8]},
        {"name": "annulus", "kind": "disk", "radius": 0.7, "inner_radius": 0.3},
    ]
    materials = [
        material("ground grey", (0.55, 0.55, 0.55), roughness=0.9),
        material("red", (0.8, 0.12, 0.1)),
        material("green", (0.15, 0.65, 0.2)),
        material("blue", (0.15, 0.25, 0.8)),
        material("yellow", (0.85, 0.7, 0.15)),
        material("mirror", (0.95, 0.95, 0.95), metallic=1.0, roughness=0.0),
        material("glass", (1.0, 1.0, 1.0), roughness=0.0,
                 extensions={"KHR_materials_transmission": {"transmissionFactor": 1.0},
                             "KHR_materials_ior": {"ior": 1.5},
                             "KHR_materials_volume": {"thicknessFactor": 1.0,
                                                      "attenuationColor": [0.85, 0.95, 0.9],
                                                      "attenuationDistance": 2.0}}),
        material("orange", (0.9, 0.4, 0.1)),
        material("white", (0.8, 0.8, 0.8)),
    ]

    def quadric_node(name, primitive, mat, translation, rotation=None, scale=None):
        node = {"name": name, "translation": tidy(translation),
                "extensions": {"KILN_quadric": {"primitive": primitive, "material": mat}}}
        if rotation:
            node["rotation"] = tidy(rotation)
        if scale:
            node["scale"] = tidy(scale)
        return node

    nodes = [
        quadric_node("ground", 0, 0, [0, 0, 0], UPRIGHT),
        quadric_node("cylinder", 1, 1, [-4.4, 0, -2.5], UPRIGHT),
        quadric_node("cone", 2, 2, [-2.2, 0, -2.5], UPRIGHT),
        quadric_node("paraboloid", 3, 3, [0.0, 0, -2.5], UPRIGHT),
        quadric_node("hyperboloid of one sheet", 4, 4, [2.2, 0.8, -2.5], UPRIGHT),
        quadric_node("hyperboloid of two sheets", 5, 7, [4.4, 0.9, -2.5], UPRIGHT),
        quadric_node("glass sphere", 6, 6, [-3.0, 0.9, 0.8], None, [0.9, 0.9, 0.9]),
        quadric_node("mirror torus", 7, 5, [0.0, 1.0, 0.6],
                     quat_mul(quat_axis_angle([0, 1, 0], 20), quat_axis_angle([1, 0, 0], -60))),
        quadric_node("saddle", 8, 4, [3.0, 0.9, 0.8], quat_mul(quat_axis_angle([0, 1, 0], 30), UPRIGHT)),
        quadric_node("ellipsoid", 6, 1, [5.3, 0.45, 1.8], quat_axis_angle([0, 1, 0], 35), [0.8, 0.45, 0.35]),
        quadric_node("mirrored annulus", 9, 8, [-5.4, 0.75, 1.6], quat_axis_angle([0, 1, 0], 40), [-1, 1, 1]),
        {"name": "camera", "camera": 0, "translation": [0.0, 4.2, 10.5],
         "rotation": tidy(quat_axis_angle([1, 0, 0], -19))},
        {"name": "key light", "translation": [-4.0, 7.0, 6.0], "extensions": {"KHR_lights_punctual": {"light": 0}}},
        {"name": "sun", "rotation": tidy(quat_mul(quat_axis_angle([0, 1, 0], 35), quat_axis_angle([1, 0, 0], -55))),
         "extensions": {"KHR_lights_punctual": {"light": 1}}},
    ]
    return {
        "asset": {"version": "2.0", "generator": "kiln tools/make_quadric_showcase.py"},
        "extensionsUsed": ["KILN_quadric", "KHR_lights_punctual", "KHR_materials_transmission", "KHR_materials_ior",
                           "KHR_materials_volume"],
        "extensions": {
            "KILN_quadric": {"primitives": primitives},
            "KHR_lights_punctual": {"lights": [
                {"name": "key", "type": "point", "color": [1.0, 0.95, 0.9], "intensity": 150.0},
                {"name": "sun", "type": "directional", "color": [0.9, 0.95, 1.0], "intensity": 1.5}]},
        },
        "scene": 0,
        "scenes": [{"nodes": list(range(len(nodes)))}],
        "nodes": nodes,
        "materials": materials,
        "cameras": [{"name": "main", "type": "perspective",
                     "perspective": {"yfov": 0.75, "aspectRatio": 1.7777778, "znear": 0.05}}],
    }


def write_scene(build_scene, default_name, description):
    """The generators' command line: writes build_scene() as JSON to --out (default scenes/NAME)."""
    parser = argparse.ArgumentParser(description=description)
    here = os.path.dirname(os.path.abspath(__file__))
    parser.add_argument("--out", default=os.path.join(here, "..", "scenes", default_name))
    args = parser.parse_args()
    with open(args.out, "w", encoding="utf-8") as f:
        json.dump(build_scene(), f, indent=1, sort_keys=False)
        f.write("\n")
    print("wrote", os.path.normpath(args.out))


def main():
    write_scene(build, "quadric_showcase.gltf", __doc__.splitlines()[0])


if __name__ == "__main__":
    main()
