// accelerator::occluded_batch on Embree (ray packets of the CPU's native width) answers, ray for
// ray, what occluded() answers: on every scene in scenes/ (triangles, quadrics, alpha-masked and
// see-through materials), on ToyCar and other models of ../shared/assets when present, still and
// with motion blur (moving instances, a deforming mesh); with invalid rays, tails shorter than a
// packet and empty batches; and again when thousands of batches run on two threads at once.
#include <gtest/gtest.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <atomic>
#include <filesystem>
#include <random>

#include "accel/embree/embree_accelerator.h"
#include "accel/grid/grid_accelerator.h"
#include "accel/grid/synthetic_scenes.h"
#include "io/gltf/gltf_loader.h"

namespace kiln {
namespace {

namespace fs = std::filesystem;

// The shipped scenes, and from the shared assets the car (many instances, see-through glass), the
// instancing and alpha-mask samples; the synthetic lattice of mirrored instances always.
std::vector<std::string> scene_names() {
  std::vector<std::string> names = {"synthetic:instanced_spheres"};
  for (const auto& e : fs::directory_iterator(fs::path(KILN_SOURCE_DIR) / "scenes"))
    if (e.path().extension() == ".gltf") names.push_back(e.path().string());
  for (const char* asset : {"ToyCar/glTF/ToyCar.gltf", "SimpleInstancing/glTF-Binary/SimpleInstancing.glb",
                            "AlphaBlendModeTest/glTF-Binary/AlphaBlendModeTest.glb"}) {
    const fs::path p = fs::path(KILN_SHARED_ASSETS) / asset;
    if (fs::is_regular_file(p)) names.push_back(p.string());
  }
  std::sort(names.begin() + 1, names.end());
  return names;
}

scene load_scene(const std::string& name) {
  if (name == "synthetic:instanced_spheres")
    return make_instanced_scene(make_sphere_mesh(24, 48, 1.0f), 3, 7);
  return load_gltf(name);
}

// Motion blur over three shutter steps: every other instance slides by a tenth of the scene's size
// and the first mesh swells by 5%, so rays at different times see different geometry.
void add_motion(scene& s) {
  const double size = std::max(glm::length(world_bounds(s).diagonal()), 1e-3);
  s.shutter.steps = 3;
  s.shutter.instance_steps.assign(s.instances.size(), {});
  s.shutter.mesh_positions.assign(s.meshes.size(), {});
  for (size_t i = 0; i < s.instances.size(); i += 2)
    for (uint32_t k = 0; k < s.shutter.steps; ++k) {
      dmat4 slide(1.0);
      slide[3] = dvec4(0.05 * size * k, -0.03 * size * k, 0.0, 1.0);
      s.shutter.instance_steps[i].push_back(slide * s.instances[i].world_from_object);
    }
  if (!s.meshes.empty())
    for (uint32_t k = 0; k < s.shutter.steps; ++k) {
      std::vector<vec3> p = s.meshes[0].positions;
      for (vec3& v : p) v *= 1.0f + 0.025f * float(k);
      s.shutter.mesh_positions[0].push_back(std::move(p));
    }
}

// Rays from inside the scene's bounds in random directions and from a sphere around it toward a
// random point inside, half of them cut short, at random shutter times; every 29th ray is invalid
// in one of the ways is_valid() refuses.
std::vector<ray> random_rays(const scene& s, size_t count, uint32_t seed) {
  const bounds3 b = world_bounds(s);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::normal_distribution<float> gauss;
  const vec3 lower(b.lower), extent(b.diagonal());
  const float radius = std::max(glm::length(extent), 1e-3f);
  auto in_box = [&] { return lower + vec3(unit(rng), unit(rng), unit(rng)) * extent; };
  auto on_sphere = [&] { return glm::normalize(vec3(gauss(rng), gauss(rng), gauss(rng)) + vec3(1e-6f)); };
  std::vector<ray> rays(count);
  for (size_t i = 0; i < count; ++i) {
    ray& r = rays[i];
    r.kind = ray_kind::shadow;
    if (i % 2 == 0) {
      r.origin = in_box();
      r.direction = on_sphere();
    } else {
      r.origin = vec3(b.center()) + 1.5f * radius * on_sphere();
      r.direction = glm::normalize(in_box() - r.origin);
    }
    if (unit(rng) < 0.5f) r.tmax = unit(rng) * radius;
    r.time = unit(rng);
    if (i % 29 == 3) switch ((i / 29) % 4) {
        case 0:
          r.direction = vec3(0.0f);
          break;
        case 1:
          r.tmin = std::nanf("");
          break;
        case 2:
          r.origin.y = inf;
          break;
        default:
          r.tmin = r.tmax + 1.0f;
          break;
      }
  }
  return rays;
}

std::vector<uint8_t> single_answers(const accelerator& accel, const std::vector<ray>& rays) {
  std::vector<uint8_t> out(rays.size());
  for (size_t i = 0; i < rays.size(); ++i) out[i] = accel.occluded(rays[i]);
  return out;
}

size_t differing(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
  size_t n = 0;
  for (size_t i = 0; i < a.size(); ++i) n += a[i] != b[i];
  return n;
}

class occlusion_batch : public ::testing::TestWithParam<std::string> {};

TEST_P(occlusion_batch, packets_answer_what_single_rays_answer) {
  for (bool moving : {false, true}) {
    SCOPED_TRACE(moving ? "with motion blur" : "still");
    scene s = load_scene(GetParam());
    if (moving) add_motion(s);
    const embree_accelerator accel(s);
    const std::vector<ray> rays = random_rays(s, 20011, 40);  // not a multiple of any packet width
    const std::vector<uint8_t> expected = single_answers(accel, rays);
    std::vector<uint8_t> blocked(rays.size(), 7);
    accel.occluded_batch(rays.data(), rays.size(), blocked.data());
    EXPECT_EQ(differing(blocked, expected), 0u);
    // Both answers occur, and every invalid ray is clear.
    const size_t hits = size_t(std::count(blocked.begin(), blocked.end(), uint8_t(1)));
    EXPECT_GT(hits, rays.size() / 50);
    EXPECT_LT(hits, rays.size() - rays.size() / 50);
    EXPECT_EQ(std::count(blocked.begin(), blocked.end(), uint8_t(0)) + hits, rays.size());
    for (size_t i = 3; i < rays.size(); i += 29) EXPECT_EQ(blocked[i], 0) << i;
    accel.throw_if_failed();
  }
}

TEST_P(occlusion_batch, every_tail_length_and_offset_matches) {
  const scene s = load_scene(GetParam());
  const embree_accelerator accel(s);
  const std::vector<ray> rays = random_rays(s, 200, 41);
  const std::vector<uint8_t> expected = single_answers(accel, rays);
  // Batches of 0..40 rays from odd offsets: partial packets, a packet of one, the invalid rays in
  // every lane position.
  for (size_t count = 0; count <= 40; ++count)
    for (size_t begin : {size_t(0), size_t(3), size_t(17), size_t(150)}) {
      std::vector<uint8_t> blocked(count + 1, 7);
      accel.occluded_batch(rays.data() + begin, count, blocked.data());
      for (size_t i = 0; i < count; ++i)
        ASSERT_EQ(blocked[i], expected[begin + i]) << count << " from " << begin;
      EXPECT_EQ(blocked[count], 7) << "wrote past the batch of " << count;
    }
}

// A shadow ray that sees only what stops light, or only what a shadow walk goes through (core/ray.h's
// ray_sees), is answered alike by Embree's packets (instance masks) and by the grid (which skips
// the other instances): ray for ray, closest hits at the same distance, each of the kind it sees.
TEST_P(occlusion_batch, rays_that_see_one_kind_of_instance_agree_with_the_grid) {
  const scene s = load_scene(GetParam());
  const embree_accelerator accel(s);
  const grid_accelerator grid(s, adaptive_grid_options());
  for (ray_sees sees : {ray_sees::light_stoppers, ray_sees::see_through_only}) {
    SCOPED_TRACE(sees == ray_sees::light_stoppers ? "light stoppers" : "see-through only");
    std::vector<ray> rays = random_rays(s, 4001, 42);
    for (ray& r : rays) r.sees = sees;
    std::vector<uint8_t> blocked(rays.size(), 7);
    accel.occluded_batch(rays.data(), rays.size(), blocked.data());
    EXPECT_EQ(differing(blocked, single_answers(accel, rays)), 0u);
    EXPECT_EQ(differing(blocked, single_answers(grid, rays)), 0u);
    size_t hits = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
      const std::optional<hit> h = accel.intersect(rays[i]), g = grid.intersect(rays[i]);
      ASSERT_EQ(h.has_value(), g.has_value()) << i;
      if (!h) continue;
      ++hits;
      // The same distance (two surfaces may meet there, so not always the same instance), and both
      // hits of the kind the ray sees.
      EXPECT_NEAR(h->t, g->t, 1e-4f * std::max(1.0f, h->t)) << i;
      for (const hit& x : {*h, *g})
        EXPECT_EQ(shadow_walks_through(s, s.instances[x.instance_id]), sees == ray_sees::see_through_only)
            << i;
    }
    // A scene with nothing of the kind is never hit by such rays.
    bool has_kind = false;
    for (const instance& inst : s.instances)
      has_kind |= shadow_walks_through(s, inst) == (sees == ray_sees::see_through_only);
    if (!has_kind) EXPECT_EQ(hits, 0u);
  }
}

INSTANTIATE_TEST_SUITE_P(scenes, occlusion_batch, ::testing::ValuesIn(scene_names()),
                         [](const ::testing::TestParamInfo<std::string>& param_info) {
                           std::string name = fs::path(param_info.param).stem().string();
                           for (char& c : name)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return name;
                         });

// The alpha-mask filter runs inside the packets (Embree hands it 16 lanes and a valid mask): the
// rays that only the cut-out texels let through must be clear in a batch too.
TEST(occlusion_batch_embree, alpha_mask_filter_answers_for_every_lane) {
  const fs::path path =
      fs::path(KILN_SHARED_ASSETS) / "AlphaBlendModeTest" / "glTF-Binary" / "AlphaBlendModeTest.glb";
  if (!fs::is_regular_file(path)) GTEST_SKIP() << path << " is not here";
  const scene s = load_gltf(path.string());
  const embree_accelerator masked(s);
  const std::vector<ray> rays = random_rays(s, 20011, 44);
  std::vector<uint8_t> blocked(rays.size());
  masked.occluded_batch(rays.data(), rays.size(), blocked.data());
  scene solid_scene = s;  // the filter reads the materials of the scene it was built over
  for (material& m : solid_scene.materials) m.alpha = alpha_mode::opaque;
  const embree_accelerator opaque(solid_scene);
  std::vector<uint8_t> solid(rays.size());
  opaque.occluded_batch(rays.data(), rays.size(), solid.data());
  size_t let_through = 0;
  for (size_t i = 0; i < rays.size(); ++i)
    if (solid[i] && !blocked[i]) {
      ++let_through;
      EXPECT_FALSE(masked.occluded(rays[i])) << i;
    }
  std::printf("%zu of %zu rays pass only through cut-out texels\n", let_through, rays.size());
  EXPECT_GT(let_through, 50u);
  EXPECT_EQ(differing(blocked, single_answers(masked, rays)), 0u);
}

TEST(occlusion_batch_embree, an_empty_batch_touches_nothing) {
  const scene s = make_instanced_scene(make_sphere_mesh(8, 16, 1.0f), 2, 3);
  const embree_accelerator accel(s);
  uint8_t untouched = 7;
  accel.occluded_batch(nullptr, 0, &untouched);
  EXPECT_EQ(untouched, 7);
}

// Thousands of batches on two threads at once, each a random slice of a fixed set of rays on the
// quadric scene (user geometry in every packet) and the instanced lattice: every answer must be
// the single-ray one. (The long soak of the same loop is bench/accel/occlusion_soak.cpp.)
TEST(occlusion_batch_embree, thousands_of_batches_on_two_threads_stay_exact) {
  const std::string quadrics = std::string(KILN_SOURCE_DIR) + "/scenes/peer_quadrics.gltf";
  for (const std::string& name : {quadrics, std::string("synthetic:instanced_spheres")}) {
    SCOPED_TRACE(name);
    scene s = load_scene(name);
    add_motion(s);
    const embree_accelerator accel(s);
    const std::vector<ray> rays = random_rays(s, 4096, 42);
    const std::vector<uint8_t> expected = single_answers(accel, rays);
    constexpr int batches = 6000;
    std::atomic<size_t> wrong{0}, answered{0};
    tbb::task_arena arena(2);
    arena.execute([&] {
      tbb::parallel_for(0, batches, [&](int b) {
        std::mt19937 rng{uint32_t(b)};
        const size_t count = std::uniform_int_distribution<size_t>(0, 96)(rng);
        const size_t begin = std::uniform_int_distribution<size_t>(0, rays.size() - count)(rng);
        std::vector<uint8_t> blocked(count);
        accel.occluded_batch(rays.data() + begin, count, blocked.data());
        for (size_t i = 0; i < count; ++i) wrong += blocked[i] != expected[begin + i];
        answered += count;
      });
    });
    EXPECT_EQ(wrong.load(), 0u);
    EXPECT_GT(answered.load(), size_t(batches) * 40);
    accel.throw_if_failed();
  }
}

// Backends without packets answer a batch one ray at a time, through the same query.
TEST(occlusion_batch_grid, the_default_batch_is_the_single_ray_query) {
  const scene s = make_instanced_scene(make_sphere_mesh(24, 48, 1.0f), 3, 7);
  const grid_accelerator grid(s, adaptive_grid_options());
  const std::vector<ray> rays = random_rays(s, 3001, 43);
  std::vector<uint8_t> blocked(rays.size(), 7);
  grid.occluded_batch(rays.data(), rays.size(), blocked.data());
  EXPECT_EQ(differing(blocked, single_answers(grid, rays)), 0u);
  EXPECT_GT(std::count(blocked.begin(), blocked.end(), uint8_t(1)), 100);
}

}  // namespace
}  // namespace kiln
