#include "support/lobe_sphere.h"

#include <OpenImageIO/imageio.h>

#include <stdexcept>

#include "accel/embree/embree_accelerator.h"
#include "io/gltf/gltf_loader.h"
#include "shade/whitted.h"
#include "support/gltf_builder.h"
#include "support/run_kiln.h"

namespace kiln::testing {
namespace {

// The rotation (x, y, z, w) that turns +z onto unit d: a directional light shines along its node's
// −z, so this node's light arrives from d.
std::array<double, 4> rotation_from_z(const dvec3& d) {
  const dvec3 z(0.0, 0.0, 1.0);
  const dvec3 axis = glm::cross(z, d);
  const double s = glm::length(axis);
  if (s < 1e-12) return d.z > 0.0 ? std::array<double, 4>{0, 0, 0, 1} : std::array<double, 4>{1, 0, 0, 0};
  const double angle = std::atan2(s, glm::dot(z, d));
  const dvec3 a = axis / s * std::sin(angle / 2.0);
  return {a.x, a.y, a.z, std::cos(angle / 2.0)};
}

// A constant 4×4 RGBA PNG.
void write_constant_png(const std::string& path, const std::array<int, 4>& rgba) {
  std::vector<uint8_t> pixels;
  for (int i = 0; i < 16; ++i)
    for (int c = 0; c < 4; ++c) pixels.push_back(uint8_t(rgba[size_t(c)]));
  auto out = OIIO::ImageOutput::create(path);
  const OIIO::ImageSpec spec(4, 4, 4, OIIO::TypeDesc::UINT8);
  if (!out || !out->open(path, spec) || !out->write_image(OIIO::TypeDesc::UINT8, pixels.data()))
    throw std::runtime_error("cannot write " + path);
  out->close();
}

}  // namespace

std::string write_lobe_sphere(const lobe_sphere& setup, const std::string& name) {
  const std::string folder = scratch_folder("lobe_sphere_" + name);
  gltf_builder b;
  for (size_t i = 0; i < setup.textures.size(); ++i) {
    const std::string file = "texture" + std::to_string(i) + ".png";
    write_constant_png(folder + "/" + file, setup.textures[i]);
    b.doc["images"].push_back({{"uri", file}});
    b.doc["textures"].push_back({{"source", int(i)}});
  }
  b.add_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {0, 1, 2});  // unplaced; the builder needs a buffer
  const int material = b.add_material(setup.material);
  b.doc["extensionsUsed"].push_back("KILN_quadric");
  for (const std::string& e : setup.extensions) b.doc["extensionsUsed"].push_back(e);
  b.doc["extensions"]["KILN_quadric"]["primitives"] = {{{"kind", setup.shape}, {"radius", 1.0}}};
  b.add_node({{"extensions", {{"KILN_quadric", {{"primitive", 0}, {"material", material}}}}}});
  const int light = b.add_light({{"type", "directional"}, {"intensity", setup.illuminance}});
  b.add_node({{"rotation", rotation_from_z(setup.to_light)},
              {"extensions", {{"KHR_lights_punctual", {{"light", light}}}}}});
  return b.write(folder + "/sphere.gltf");
}

std::vector<lobe_ray> trace_lobe_sphere(const lobe_sphere& setup, const std::string& name) {
  const scene world = load_gltf(write_lobe_sphere(setup, name));
  const embree_accelerator accel(world);
  const shading_options options;
  const shading_context ctx{world, accel, options};
  std::vector<lobe_ray> out;
  for (int j = 0; j < setup.grid; ++j)
    for (int i = 0; i < setup.grid; ++i) {
      // Cell centres across [-1, 1]².
      const double x = -1.0 + (2.0 * i + 1.0) / setup.grid;
      const double y = -1.0 + (2.0 * j + 1.0) / setup.grid;
      const double rho2 = x * x + y * y;
      if (rho2 > setup.max_radius * setup.max_radius || rho2 < setup.min_radius * setup.min_radius) continue;
      const bool disk = setup.shape == "disk";
      ray r;
      r.origin = vec3(float(x), float(y), 10.0f);
      r.direction = vec3(0.0f, 0.0f, -1.0f);
      r.kind = ray_kind::camera;
      ray_counts counts;
      lobe_ray l;
      l.normal = disk ? dvec3(0.0, 0.0, 1.0) : dvec3(x, y, std::sqrt(1.0 - rho2));
      l.tangent = disk ? dvec3(1.0, 0.0, 0.0) : dvec3(-y, x, 0.0) / std::max(std::sqrt(rho2), 1e-300);
      l.to_viewer = dvec3(0.0, 0.0, 1.0);
      l.to_light = setup.to_light;
      l.radiance = trace_radiance(ctx, r, path_state{}, counts);
      out.push_back(l);
    }
  return out;
}

}  // namespace kiln::testing
