// Embree, the uniform grid and the adaptive grid answer the same random rays (fixed seed, origins
// inside and outside the scene, some segments cut short for occlusion) on every scene in scenes/,
// on generated scenes (an instanced one with mirrored placements, a triangle soup) and, when
// ../shared/assets exists, on every model there. Zero mismatches beyond the hit's error bound;
// wherever two backends differ at all (a tie or an edge graze), the brute-force loop over every
// triangle decides, and the grid must match it exactly.
#include <gtest/gtest.h>

#include <filesystem>
#include <random>

#include "accel/compare/hit_comparison.h"
#include "accel/embree/embree_accelerator.h"
#include "accel/grid/brute_force_accelerator.h"
#include "accel/grid/grid_accelerator.h"
#include "accel/grid/synthetic_scenes.h"
#include "geometry/triangle.h"
#include "io/gltf/gltf_loader.h"

namespace kiln {
namespace {

namespace fs = std::filesystem;

constexpr int rays_per_scene = 100000;
// The brute-force tie-breaker loops over every triangle, so it is capped by total work (checks ×
// triangles): a small scene checks every differing ray, a huge one of coincident copies (which
// ties on nearly every ray) a sample.
constexpr double max_brute_force_work = 2e8;
// Barycentrics of the same triangle hit: Embree and the watertight test round differently, but
// both solve for the same point.
constexpr float max_barycentric_difference = 1e-3f;

std::vector<std::string> scene_names() {
  std::vector<std::string> names = {"synthetic:instanced_spheres", "synthetic:soup"};
  for (const auto& e : fs::directory_iterator(fs::path(KILN_SOURCE_DIR) / "scenes"))
    if (e.path().extension() == ".gltf" || e.path().extension() == ".glb") names.push_back(e.path().string());
  fs::path root(KILN_SHARED_ASSETS);
  std::error_code ec;
  if (fs::is_directory(root, ec))
    for (auto it = fs::recursive_directory_iterator(root, ec); it != fs::recursive_directory_iterator();
         ++it) {
      if (it->path().filename() == "invalid") {
        it.disable_recursion_pending();
        continue;
      }
      std::string ext = it->path().extension().string();
      if (ext == ".gltf" || ext == ".glb") names.push_back(it->path().string());
    }
  std::sort(names.begin() + 2, names.end());
  return names;
}

std::optional<scene> load_scene(const std::string& name) {
  if (name == "synthetic:instanced_spheres")
    return make_instanced_scene(make_sphere_mesh(24, 48, 1.0f), 4, 21);
  if (name == "synthetic:soup") return scene_from_mesh(make_triangle_soup(20000, 5, 1.0f, 0.08f));
  try {
    return load_gltf(name);
  } catch (const error& e) {
    // Only a refused required extension (e.g. KHR_texture_basisu) is skipped; the asset suite covers
    // that refusal. Any other loader failure is a regression and fails here.
    if (e.location().rfind("/extensionsRequired", 0) == 0) return std::nullopt;
    throw;
  }
}

size_t triangle_count(const scene& s) {
  size_t n = 0;
  for (const instance& inst : s.instances)
    if (inst.kind == shape_kind::mesh) n += s.meshes[inst.shape].triangle_count();
  return n;
}

// Half the rays start inside the scene bounds in random directions; half start on a sphere around
// it and aim at a random point inside. Every third segment ends at a random distance.
std::vector<ray> random_rays(const bounds3& b, int count, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::normal_distribution<double> gauss;
  // Inside origins come from the bounds grown by a tenth of their diagonal on every axis, so a flat
  // scene does not start every inside ray on its own surface.
  const double radius = std::max(glm::length(b.diagonal()), 1e-6);
  const dvec3 centre = b.center(), extent = b.diagonal() + dvec3(0.2 * radius);
  const dvec3 lower = b.lower - dvec3(0.1 * radius);
  auto in_box = [&] { return lower + dvec3(unit(rng), unit(rng), unit(rng)) * extent; };
  auto on_sphere = [&] { return glm::normalize(dvec3(gauss(rng), gauss(rng), gauss(rng)) + dvec3(1e-12)); };
  std::vector<ray> rays;
  rays.reserve(size_t(count));
  for (int i = 0; i < count; ++i) {
    ray r;
    if (i % 2 == 0) {
      r.origin = vec3(in_box());
      r.direction = vec3(on_sphere());
    } else {
      dvec3 o = centre + 1.5 * radius * on_sphere();
      r.origin = vec3(o);
      r.direction = vec3(glm::normalize(in_box() - o));
    }
    if (i % 3 == 0) r.tmax = float(unit(rng) * 2.0 * radius);
    rays.push_back(r);
  }
  return rays;
}

bool identical(const std::optional<hit>& a, const std::optional<hit>& b) {
  if (!a || !b) return !a && !b;
  return a->instance_id == b->instance_id && a->primitive_id == b->primitive_id && a->t == b->t &&
         a->u == b->u && a->v == b->v;
}

struct tally {
  size_t hits = 0, mismatches = 0, ties = 0, edges = 0, occlusion_mismatches = 0, brute_force_checks = 0,
         barycentric_mismatches = 0, widened_barycentric_bounds = 0;
  float max_barycentric_difference = 0.0f;
};

// Occlusion answers that differ must come from a blocker on an edge or at the segment's end.
bool occlusion_agrees(const scene& s, const ray& r, bool a, bool b, const std::optional<hit>& a_hit,
                      const std::optional<hit>& b_hit) {
  if (a == b) return true;
  const std::optional<hit>& blocker = a ? a_hit : b_hit;
  return blocker && hit_on_boundary(s, r, *blocker);
}

// How far the grid's (u, v) may stray from Embree's on the same triangle. The two backends put the
// hit at slightly different t (a few ulps of t, more on grazing rays: t ≈ 90 on the instanced
// spheres), and that slide of |Δt|·|d| along the ray moves u (v) by at most the slide over the
// height of p1 (p2) above the opposite edge. So: max_barycentric_difference plus twice the slide
// over the smaller height (twice: each backend's own rounding of u, v comes on top, measured at
// up to 1.8x the slide term). A swap of u and v, or another convention, shows at any Δt.
float barycentric_tolerance(const scene& s, const ray& r, const hit& e, const hit& g) {
  const instance& inst = s.instances[e.instance_id];
  auto p = triangle_vertices(s.meshes[inst.shape], e.primitive_id);
  dvec3 w[3];
  for (int i = 0; i < 3; ++i) w[i] = transform_point(inst.world_from_object, dvec3(p[i]));
  const double twice_area = glm::length(glm::cross(w[1] - w[0], w[2] - w[0]));
  const double height = twice_area / std::max(glm::length(w[2] - w[0]), glm::length(w[1] - w[0]));
  const double slide = std::abs(double(e.t) - double(g.t)) * glm::length(dvec3(r.direction));
  return max_barycentric_difference + (height > 0.0 ? float(2.0 * slide / height) : inf);
}

class crosscheck : public ::testing::TestWithParam<std::string> {};

TEST_P(crosscheck, grid_adaptive_grid_and_embree_agree) {
  std::optional<scene> loaded = load_scene(GetParam());
  if (!loaded) GTEST_SKIP() << "not loadable (unsupported extension)";
  const scene& s = *loaded;
  const bounds3 b = world_bounds(s);
  if (b.empty()) GTEST_SKIP() << "no geometry";

  embree_accelerator embree(s);
  grid_accelerator uniform(s, uniform_grid_options());
  grid_accelerator adaptive(s, adaptive_grid_options());
  brute_force_accelerator brute(s);
  const size_t max_brute_force_checks =
      size_t(max_brute_force_work / double(std::max<size_t>(1, triangle_count(s) + s.instances.size())));

  tally t;
  const std::vector<ray> rays = random_rays(b, rays_per_scene, 1234);
  for (size_t i = 0; i < rays.size(); ++i) {
    const ray& r = rays[i];
    const std::optional<hit> e = embree.intersect(r), g = uniform.intersect(r), a = adaptive.intersect(r);
    t.hits += e.has_value();
    // The two grids use the same triangle test and tie rule: they must agree bit for bit.
    if (!identical(g, a)) {
      ++t.mismatches;
      ADD_FAILURE() << "uniform and adaptive grid differ on ray " << i;
    }
    switch (compare_hits(s, r, e, g)) {
      case hit_verdict::agree:
        // The same triangle hit: (u, v) must follow Embree's convention, not just t.
        if (e && g && e->primitive_id == g->primitive_id &&
            s.instances[e->instance_id].kind == shape_kind::mesh) {
          const float du = std::abs(e->u - g->u), dv = std::abs(e->v - g->v);
          t.max_barycentric_difference = std::max({t.max_barycentric_difference, du, dv});
          const float bound = barycentric_tolerance(s, r, *e, *g);
          t.widened_barycentric_bounds +=
              (du >= max_barycentric_difference || dv >= max_barycentric_difference);
          if ((du >= bound || dv >= bound) && ++t.barycentric_mismatches <= 5)
            ADD_FAILURE() << "ray " << i << ": u,v embree " << e->u << "," << e->v << " grid " << g->u << ","
                          << g->v << " (bound " << bound << ", cos "
                          << glm::dot(glm::normalize(r.direction), e->geometric_normal) << ")";
        }
        break;
      case hit_verdict::tie:
        ++t.ties;
        break;
      case hit_verdict::edge:
        ++t.edges;
        break;
      case hit_verdict::mismatch:
        if (++t.mismatches <= 5)
          ADD_FAILURE() << "ray " << i << ": embree " << (e ? int(e->primitive_id) : -1) << " t "
                        << (e ? e->t : -1.0f) << ", grid " << (g ? int(g->primitive_id) : -1) << " t "
                        << (g ? g->t : -1.0f) << " (tolerance " << (e ? hit_t_tolerance(s, r, *e) : 0.0f)
                        << ", u,v embree " << (e ? e->u : -1.0f) << "," << (e ? e->v : -1.0f) << " grid "
                        << (g ? g->u : -1.0f) << "," << (g ? g->v : -1.0f) << ", cos "
                        << (e ? glm::dot(r.direction, e->geometric_normal) : 0.0f) << ", tmax " << r.tmax
                        << ")";
        break;
    }
    // Wherever Embree and the grid differ at all, the brute-force loop is the tie-breaker.
    // (Capped by work: a scene of coincident copies ties on every ray, and each check loops over
    // everything.)
    if (!(e && g && e->instance_id == g->instance_id && e->primitive_id == g->primitive_id) && (e || g) &&
        t.brute_force_checks < max_brute_force_checks) {
      ++t.brute_force_checks;
      EXPECT_TRUE(identical(g, brute.intersect(r))) << "grid differs from brute force on ray " << i;
    }
    const bool eo = embree.occluded(r), go = uniform.occluded(r), ao = adaptive.occluded(r);
    EXPECT_EQ(go, ao) << "grids disagree on occlusion of ray " << i;
    EXPECT_EQ(go, g.has_value()) << "grid occlusion and closest hit disagree on ray " << i;
    if (!occlusion_agrees(s, r, eo, go, e, g)) ++t.occlusion_mismatches;
  }
  EXPECT_EQ(t.mismatches, 0u);
  EXPECT_EQ(t.occlusion_mismatches, 0u);
  EXPECT_EQ(t.barycentric_mismatches, 0u);
  EXPECT_GT(t.hits, 0u);
  // Edge grazes are legitimate but must stay rare on random rays. Ties are not bounded: an asset
  // may place coincident copies (RecursiveSkeletons ties on nearly every ray).
  EXPECT_LT(t.edges, rays.size() / 100);
  std::printf(
      "%s: %zu rays, %zu hits, %zu ties, %zu edge cases, %zu brute-force checks (cap %zu), "
      "max |du|,|dv| %.2g (%zu above %.0e, explained by their |dt|)\n",
      GetParam().c_str(), rays.size(), t.hits, t.ties, t.edges, t.brute_force_checks, max_brute_force_checks,
      double(t.max_barycentric_difference), t.widened_barycentric_bounds, double(max_barycentric_difference));
}

INSTANTIATE_TEST_SUITE_P(scenes, crosscheck, ::testing::ValuesIn(scene_names()),
                         [](const ::testing::TestParamInfo<std::string>& param_info) {
                           std::string name = fs::path(param_info.param).stem().string() + "_" +
                                              std::to_string(param_info.index);
                           for (char& c : name)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return name;
                         });

}  // namespace
}  // namespace kiln
