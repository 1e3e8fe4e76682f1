#include "app/compare_command.h"

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "accel/compare/comparing_accelerator.h"
#include "accel/make_accelerator.h"
#include "app/cli_checks.h"
#include "app/interrupt.h"
#include "app/text_output.h"
#include "core/error.h"
#include "io/exr/exr_writer.h"
#include "render/render_space.h"

namespace kiln {

namespace {

struct image_difference {
  double rmse = 0.0;            // over the RGBA channels of every pixel
  double max_difference = 0.0;  // largest channel difference
  uint64_t differing_pixels = 0;
  film mask;  // RGB = 1 where a pixel differs; Z = |Δdepth|
};

bool differs(double a, double b, double tolerance) {
  if (std::isinf(a) || std::isinf(b)) return a != b;
  return std::abs(a - b) > tolerance * std::max(1.0, std::max(std::abs(a), std::abs(b)));
}

// Pixel-by-pixel difference of two renders of the same view; depth and normal count too, so a
// camera ray that found another surface shows even where the colours happen to match.
image_difference compare_images(const film& a, const film& b, double tolerance) {
  image_difference d;
  d.mask = film(a.width, a.height);
  double sum = 0.0;
  for (size_t i = 0; i < a.color.size(); ++i) {
    bool pixel_differs = false;
    for (int c = 0; c < 4; ++c) {
      double delta = std::abs(double(a.color[i][c]) - double(b.color[i][c]));
      sum += delta * delta;
      d.max_difference = std::max(d.max_difference, delta);
      pixel_differs |= differs(a.color[i][c], b.color[i][c], tolerance);
    }
    pixel_differs |= differs(a.depth[i], b.depth[i], tolerance);
    for (int c = 0; c < 3; ++c)
      pixel_differs |= differs(a.vec3_layer(aov::normal)[i][c], b.vec3_layer(aov::normal)[i][c], tolerance);
    d.differing_pixels += pixel_differs;
    d.mask.color[i] = pixel_differs ? vec4(1.0f) : vec4(0.0f, 0.0f, 0.0f, 1.0f);
    d.mask.depth[i] =
        std::isinf(a.depth[i]) && std::isinf(b.depth[i]) ? 0.0f : std::abs(a.depth[i] - b.depth[i]);
  }
  d.rmse = a.color.empty() ? 0.0 : std::sqrt(sum / (4.0 * double(a.color.size())));
  return d;
}

nlohmann::json hit_json(const std::optional<hit>& h) {
  if (!h) return nullptr;
  return {
      {"t", h->t}, {"instance", h->instance_id}, {"primitive", h->primitive_id}, {"u", h->u}, {"v", h->v}};
}

// Sizes of a grid backend's structure (null for Embree), so a report shows what --grid-* built.
nlohmann::json structure_json(const accelerator& accel) {
  std::optional<grid_statistics> g = accelerator_grid_statistics(accel);
  if (!g) return nullptr;
  return {{"nodes", g->nodes},
          {"cells", g->cells},
          {"item_references", g->item_references},
          {"memory_bytes", g->memory_bytes}};
}

nlohmann::json grid_options_json(const grid_options& g) {
  nlohmann::json resolution = nullptr;
  if (g.resolution) resolution = {g.resolution->x, g.resolution->y, g.resolution->z};
  return {{"density", g.density},
          {"resolution", resolution},
          {"max_items", g.max_items_per_cell},
          {"max_depth", g.max_depth}};
}

nlohmann::json report_json(const compare_options& o, const view_camera& cam, const accelerator& tested,
                           const accelerator& reference, const comparison_statistics& rays,
                           const image_difference& image, bool agree) {
  nlohmann::json kinds = nlohmann::json::object();
  for (ray_kind k :
       {ray_kind::camera, ray_kind::shadow, ray_kind::reflection, ray_kind::refraction, ray_kind::other}) {
    const kind_statistics& s = rays.by_kind[size_t(k)];
    if (k == ray_kind::other && s.rays == 0) continue;
    kinds[ray_kind_name(k)] = {{"rays", s.rays},
                               {"closest_hit_queries", s.closest_hit_queries},
                               {"occlusion_queries", s.occlusion_queries},
                               {"closest_hit_mismatches", s.closest_hit_mismatches},
                               {"occlusion_mismatches", s.occlusion_mismatches},
                               {"ties", s.ties},
                               {"edge_cases", s.edge_cases},
                               {"max_relative_dt", s.max_relative_dt}};
  }
  nlohmann::json examples = nlohmann::json::array();
  for (const mismatch_example& e : rays.examples)
    examples.push_back(
        {{"kind", ray_kind_name(e.query.kind)},
         {"origin", {e.query.origin.x, e.query.origin.y, e.query.origin.z}},
         {"direction", {e.query.direction.x, e.query.direction.y, e.query.direction.z}},
         {"tmin", e.query.tmin},
         {"tmax", std::isinf(e.query.tmax) ? nlohmann::json("inf") : nlohmann::json(e.query.tmax)},
         {"occlusion", e.occlusion},
         {o.accel, e.occlusion ? nlohmann::json(e.primary_occluded) : hit_json(e.primary)},
         {o.against, e.occlusion ? nlohmann::json(e.secondary_occluded) : hit_json(e.secondary)}});
  return {{"asset", o.view.input},
          {"accel", o.accel},
          {"against", o.against},
          {"width", cam.width},
          {"height", cam.height},
          {"samples_per_pixel", samples_per_pixel_of(o.view)},
          {"grid_options", grid_options_json(o.view.grid)},
          {"structure", {{"accel", structure_json(tested)}, {"against", structure_json(reference)}}},
          {"rays", kinds},
          {"mismatches", rays.mismatches()},
          {"max_mismatches", o.max_mismatches},
          {"image",
           {{"rmse", image.rmse},
            {"max_difference", image.max_difference},
            {"differing_pixels", image.differing_pixels},
            {"pixels", uint64_t(cam.width) * uint64_t(cam.height)},
            {"pixel_tolerance", o.pixel_tolerance}}},
          {"examples", examples},
          {"agree", agree}};
}

void print_summary(const compare_options& o, const accelerator& tested, const accelerator& reference,
                   const comparison_statistics& rays, const image_difference& image, bool agree) {
  std::fprintf(stderr, "kiln compare: %s against %s\n", o.accel.c_str(), o.against.c_str());
  auto print_structure = [](const std::string& name, const accelerator& accel) {
    if (std::optional<grid_statistics> g = accelerator_grid_statistics(accel))
      std::fprintf(stderr, "  %s: %zu nodes, %zu cells, %zu item references, %.1f MB\n", name.c_str(),
                   g->nodes, g->cells, g->item_references, double(g->memory_bytes) / 1e6);
  };
  print_structure(o.accel, tested);
  print_structure(o.against, reference);
  std::fprintf(stderr, "  %-11s %12s %12s %12s %8s %8s %14s\n", "ray kind", "rays", "hit mism.",
               "occl. mism.", "ties", "edges", "max |dt|/t");
  for (ray_kind k : {ray_kind::camera, ray_kind::shadow, ray_kind::reflection, ray_kind::refraction}) {
    const kind_statistics& s = rays.by_kind[size_t(k)];
    std::fprintf(stderr, "  %-11s %12llu %12llu %12llu %8llu %8llu %14.3g\n", ray_kind_name(k),
                 (unsigned long long)s.rays, (unsigned long long)s.closest_hit_mismatches,
                 (unsigned long long)s.occlusion_mismatches, (unsigned long long)s.ties,
                 (unsigned long long)s.edge_cases, s.max_relative_dt);
  }
  std::fprintf(stderr, "  image: RMSE %.3g, max difference %.3g, %llu differing pixels\n", image.rmse,
               image.max_difference, (unsigned long long)image.differing_pixels);
  std::fprintf(stderr, "  %s\n", agree ? "backends agree" : "backends DISAGREE beyond tolerance");
}

}  // namespace

void add_compare_options(CLI::App& app, compare_options& o) {
  add_view_options(app, o.view);
  const auto backends = CLI::IsMember({"embree", "grid", "adaptive-grid"});
  app.add_option("--accel", o.accel, "Backend under test")->check(backends)->capture_default_str();
  app.add_option("--against", o.against, "Reference backend")->check(backends)->capture_default_str();
  app.add_option("--mask", o.mask,
                 "Write a mismatch-mask EXR (RGB 1 where pixels differ, Z = |depth difference|)");
  app.add_option("--json", o.json, "Write a JSON report");
  app.add_option("--pixel-tolerance", o.pixel_tolerance,
                 "Channel difference (relative above 1) counted as differing")
      ->check(finite_number())
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  app.add_option("--max-mismatches", o.max_mismatches,
                 "Ray mismatches beyond error bounds tolerated before exit 3")
      ->capture_default_str();
}

int run_compare(const compare_options& o) {
  if (!o.mask.empty()) check_output_writable(o.mask);
  if (!o.json.empty()) check_output_writable(o.json);
  prepared_scene prepared = prepare_cli_scene(o.view);
  const scene& world = prepared.world;
  std::unique_ptr<accelerator> tested =
      make_accelerator(world, *parse_accel_kind(o.accel), o.view.grid, o.view.embree);
  std::unique_ptr<accelerator> reference =
      make_accelerator(world, *parse_accel_kind(o.against), o.view.grid, o.view.embree);
  render_settings settings = make_render_settings(o.view);
  settings.cancel = &interrupt_requested();

  // One render asks both backends every query; a second renders the reference image alone.
  comparing_accelerator both(world, *tested, *reference);
  const film tested_image = render_image(world, both, prepared.cam, settings);
  const film reference_image = render_image(world, *reference, prepared.cam, settings);
  const comparison_statistics rays = both.statistics();
  const image_difference image = compare_images(tested_image, reference_image, o.pixel_tolerance);
  const bool agree = backends_agree(rays, o.max_mismatches);

  if (!o.mask.empty()) {
    exr_metadata metadata;
    metadata.world_to_camera = world_to_camera(world_space_view(prepared.cam, prepared.world));
    metadata.world_to_ndc = world_to_ndc(world_space_view(prepared.cam, prepared.world));
    metadata.attributes = {{"kiln/scene_file", o.view.input}, {"kiln/mask", o.accel + " vs " + o.against}};
    write_exr(o.mask, image.mask, exr_settings{}, metadata);
  }
  if (!o.json.empty())
    write_text_atomically(
        o.json, report_json(o, prepared.cam, *tested, *reference, rays, image, agree).dump(2) + "\n");
  if (!o.view.quiet) print_summary(o, *tested, *reference, rays, image, agree);
  return agree ? 0 : exit_backends_disagree;
}

}  // namespace kiln
