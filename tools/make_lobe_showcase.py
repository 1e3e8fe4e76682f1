#!/usr/bin/env python3
"""Generate scenes/lobe_showcase.gltf: one analytic sphere per glTF material extension lobe.

World is glTF's: metres, +Y up. On a grey ground disk, left to right:

  clearcoat     red rough dielectric under a smooth coat (KHR_materials_clearcoat)
  sheen         dark blue base with a pale Charlie sheen (KHR_materials_sheen)
  iridescence   a smooth dark metal under a 380 nm film (KHR_materials_iridescence)
  anisotropy    brushed metal: the highlight stretched around the sphere's axis
                (KHR_materials_anisotropy, along each sphere's dp/du)
  dispersion    a glass ball of Abbe number 6.7 in front of a small bright disk (KHR_materials_dispersion)
  specular      a dielectric whose highlight is tinted gold (KHR_materials_specular)

and at the back an upright green disk that transmits light diffusely (a leaf,
KHR_materials_diffuse_transmission), lit from behind by its own lamp. Python 3 standard library
only; the output is deterministic JSON.

Usage: python3 tools/make_lobe_showcase.py [--out scenes/lobe_showcase.gltf]
"""

# The quadric showcase's helpers: placement quaternions, the material record, the command line.
from make_quadric_showcase import UPRIGHT, material, quat_axis_angle, tidy, write_scene


def build():
    primitives = [
        {"name": "ground", "kind": "disk", "radius": 14.0},
        {"name": "ball", "kind": "sphere", "radius": 0.8},
        {"name": "leaf", "kind": "disk", "radius": 1.3},
        {"name": "spot", "kind": "disk", "radius": 0.25},
    ]
    materials = [
        material("ground", (0.55, 0.55, 0.55), roughness=0.9),
        material("clearcoat", (0.7, 0.05, 0.05), roughness=0.6,
                 extensions={"KHR_materials_clearcoat": {"clearcoatFactor": 1.0, "clearcoatRoughnessFactor": 0.03}}),
        material("sheen", (0.03, 0.05, 0.25), roughness=0.9,
                 extensions={"KHR_materials_sheen": {"sheenColorFactor": [0.9, 0.85, 1.0],
                                                     "sheenRoughnessFactor": 0.4}}),
        material("iridescence", (0.15, 0.15, 0.18), metallic=1.0, roughness=0.08,
                 extensions={"KHR_materials_iridescence": {"iridescenceFactor": 1.0, "iridescenceIor": 1.4,
                                                           "iridescenceThicknessMaximum": 380.0}}),
        material("anisotropy", (0.9, 0.9, 0.92), metallic=1.0, roughness=0.3,
                 extensions={"KHR_materials_anisotropy": {"anisotropyStrength": 0.9}}),
        material("dispersion", (1.0, 1.0, 1.0), roughness=0.0,
                 extensions={"KHR_materials_transmission": {"transmissionFactor": 1.0},
                             "KHR_materials_volume": {"thicknessFactor": 1.6},
                             "KHR_materials_ior": {"ior": 1.6},
                             "KHR_materials_dispersion": {"dispersion": 3.0}}),
        material("specular", (0.05, 0.05, 0.06), roughness=0.25,
                 extensions={"KHR_materials_specular": {"specularFactor": 1.0,
                                                        "specularColorFactor": [2.0, 1.5, 0.5]}}),
        material("leaf", (0.1, 0.35, 0.05), roughness=0.6,
                 extensions={"KHR_materials_diffuse_transmission": {
                     "diffuseTransmissionFactor": 0.6, "diffuseTransmissionColorFactor": [0.6, 0.9, 0.1]}}),
        material("spot", (1.0, 1.0, 1.0), extensions={"KHR_materials_unlit": {}}),
    ]
    materials[-2]["doubleSided"] = True

    def quadric_node(name, primitive, mat, translation, rotation=None):
        node = {"name": name, "translation": translation,
                "extensions": {"KILN_quadric": {"primitive": primitive, "material": mat}}}
        if rotation:
            node["rotation"] = rotation
        return node

    spheres = ["clearcoat", "sheen", "iridescence", "anisotropy", "dispersion", "specular"]
    nodes = [quadric_node("ground", 0, 0, [0.0, 0.0, 0.0], UPRIGHT)]
    for i, name in enumerate(spheres):
        # Upright: the anisotropy follows the sphere's dp/du, around its (now vertical) axis.
        nodes.append(quadric_node(name, 1, i + 1, [round(-4.5 + 1.8 * i, 7) + 0.0, 0.8, 0.0], UPRIGHT))
    nodes.append(quadric_node("leaf", 2, 7, [0.0, 1.6, -3.0]))
    # A small bright unlit disk behind the glass ball: the ball images it, and its dispersion
    # fringes the image's edges red and blue.
    nodes.append(quadric_node("spot", 3, 8, [3.3, 0.4, -1.9]))
    nodes += [
        {"name": "camera", "camera": 0, "translation": [0.0, 3.0, 8.5],
         "rotation": tidy(quat_axis_angle([1, 0, 0], -16))},
        {"name": "key light", "translation": [-3.0, 6.0, 5.0], "extensions": {"KHR_lights_punctual": {"light": 0}}},
        {"name": "back light", "translation": [0.5, 2.2, -6.0],
         "extensions": {"KHR_lights_punctual": {"light": 1}}},
    ]
    return {
        "asset": {"version": "2.0", "generator": "kiln tools/make_lobe_showcase.py"},
        "extensionsUsed": ["KILN_quadric", "KHR_lights_punctual", "KHR_materials_clearcoat", "KHR_materials_sheen",
                           "KHR_materials_iridescence", "KHR_materials_anisotropy", "KHR_materials_transmission",
                           "KHR_materials_volume", "KHR_materials_ior", "KHR_materials_dispersion",
                           "KHR_materials_specular", "KHR_materials_diffuse_transmission", "KHR_materials_unlit"],
        "extensions": {
            "KILN_quadric": {"primitives": primitives},
            "KHR_lights_punctual": {"lights": [
                {"name": "key", "type": "point", "color": [1.0, 0.96, 0.9], "intensity": 120.0},
                {"name": "back", "type": "point", "color": [1.0, 0.9, 0.7], "intensity": 12.0}]},
        },
        "scene": 0,
        "scenes": [{"nodes": list(range(len(nodes)))}],
        "nodes": nodes,
        "materials": materials,
        "cameras": [{"name": "main", "type": "perspective",
                     "perspective": {"yfov": 0.7, "aspectRatio": 1.7777778, "znear": 0.05}}],
    }


def main():
    write_scene(build, "lobe_showcase.gltf", __doc__.splitlines()[0])


if __name__ == "__main__":
    main()
