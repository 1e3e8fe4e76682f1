// A kept scene (job/loaded_scene.h) renders what run_job renders from the same options, pixel for
// pixel and with the same settings hash, whatever the renders before it asked for: another view,
// size, sampling, lighting, region, time or variant. Renders from two threads both finish right,
// and each render gives its memory back.
#include "job/loaded_scene.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <thread>
#include <type_traits>
#include <utility>
#include <vector>

#include "core/error.h"
#include "job/asset_info.h"
#include "job/option_table.h"

namespace kiln {
namespace {

namespace fs = std::filesystem;

const std::string cornell = KILN_SOURCE_DIR "/scenes/cornell_box.gltf";

using option_list = std::vector<std::pair<std::string, std::string>>;

render_job job_of(const std::string& asset, const option_list& options) {
  render_job job;
  job.options.input = asset;
  for (const auto& [name, value] :
       option_list{{"width", "24"}, {"height", "18"}, {"spp", "2"}, {"threads", "2"}})
    set_render_option(job.options, name, value);
  for (const auto& [name, value] : options) set_render_option(job.options, name, value);
  return job;
}

// A text attribute of the EXR header (held as text, or as the text alternative of a typed value).
template <typename value_type>
std::string text_of(const value_type& value) {
  if constexpr (std::is_same_v<value_type, std::string>)
    return value;
  else
    return std::get<std::string>(value);
}

std::string attribute(const render_job_result& r, const std::string& name) {
  for (const auto& [key, value] : r.metadata.attributes)
    if (key == name) return text_of(value);
  return "";
}

// The kept scene's render of options equals run_job's, every layer and the settings hash.
void expect_same_as_run_job(loaded_scene& kept, const std::string& asset, const option_list& options) {
  SCOPED_TRACE(::testing::PrintToString(options));
  const render_job_result ours = kept.render(job_of(asset, options));
  const render_job_result alone = run_job(job_of(asset, options));
  ASSERT_EQ(ours.image.width, alone.image.width);
  ASSERT_EQ(ours.image.height, alone.image.height);
  EXPECT_EQ(ours.image.color, alone.image.color);
  EXPECT_EQ(ours.image.depth, alone.image.depth);
  EXPECT_EQ(ours.camera_description, alone.camera_description);
  EXPECT_EQ(attribute(ours, "kiln/settings_hash"), attribute(alone, "kiln/settings_hash"));
  EXPECT_EQ(attribute(ours, "kiln/input_hash"), attribute(alone, "kiln/input_hash"));
  float lit = 0.0f;
  for (const vec4& c : ours.image.color) lit += c.r + c.g + c.b;
  EXPECT_GT(lit, 0.1f);  // not a black picture
}

TEST(loaded_scene, renders_what_run_job_renders_whatever_came_before) {
  loaded_scene kept(job_of(cornell, {}));
  for (const option_list& options :
       {option_list{},
        {{"look-from", "0.2,1,3.5"}, {"look-at", "0,1,0"}, {"width", "20"}, {"height", "20"}},
        {{"spp", "4"}, {"aovs", "beauty,Z,N,albedo"}},
        {{"crop", "3,2,15,12"}},
        {{"lighting", "headlight"}},
        {{"background", "0.2,0.3,0.4"}, {"show-background", "true"}},
        {{"accel", "grid"}},
        {{"camera-view", "top"}},
        {{"holdout", "left_wall_red"}},
        option_list{}})
    expect_same_as_run_job(kept, cornell, options);
}

TEST(loaded_scene, an_option_that_changes_the_load_renders_as_run_job_and_keeps_the_scene) {
  const render_job base = job_of(cornell, {});
  EXPECT_EQ(
      changed_load_option(base.options, job_of(cornell, {{"spp", "8"}, {"camera-view", "top"}}).options), "");
  EXPECT_EQ(changed_load_option(base.options, job_of(cornell, {{"scene", "0"}}).options), "scene");
  EXPECT_EQ(changed_load_option(base.options, job_of(cornell, {{"max-nodes", "100"}}).options), "max-nodes");
  render_job other = base;
  other.options.input = KILN_SOURCE_DIR "/scenes/quadric_showcase.gltf";
  EXPECT_EQ(changed_load_option(base.options, other.options), "input");

  loaded_scene kept(base);
  expect_same_as_run_job(kept, cornell, {{"max-nodes", "100"}});
  EXPECT_EQ(kept.options().limits.max_nodes, base.options.limits.max_nodes);  // still as loaded
  // A limit the file breaks refuses that render alone, as run_job refuses it.
  EXPECT_THROW(kept.render(job_of(cornell, {{"max-nodes", "1"}})), error);
  expect_same_as_run_job(kept, cornell, {});
}

TEST(loaded_scene, an_animated_file_renders_each_time_and_variant_as_run_job) {
  const std::string animated = KILN_SHARED_ASSETS "/BoxAnimated/glTF-Binary/BoxAnimated.glb";
  const std::string shoe = KILN_SHARED_ASSETS "/MaterialsVariantsShoe/glTF/MaterialsVariantsShoe.gltf";
  if (!fs::exists(animated) || !fs::exists(shoe)) GTEST_SKIP() << "the shared assets are absent";
  loaded_scene box(job_of(animated, {}));
  for (const char* time : {"1.5", "0.25", "3"})  // the default camera frames every pose
    expect_same_as_run_job(box, animated, {{"time", time}});
  expect_same_as_run_job(box, animated, {{"frame", "30"}, {"look-from", "3,2,6"}, {"look-at", "0,0,0"}});
  expect_same_as_run_job(box, animated, {{"time", "1.5"}});

  loaded_scene shoes(job_of(shoe, {}));
  expect_same_as_run_job(shoes, shoe, {{"variant", "1"}});
  expect_same_as_run_job(shoes, shoe, {});
}

TEST(loaded_scene, a_failed_render_leaves_the_scene_to_render_again) {
  loaded_scene kept(job_of(cornell, {}));
  expect_same_as_run_job(kept, cornell, {{"spp", "1"}});
  EXPECT_THROW(kept.render(job_of(cornell, {{"camera", "no such camera"}})), error);
  EXPECT_THROW(kept.render(job_of(cornell, {{"crop", "0,0,500,500"}})), error);
  expect_same_as_run_job(kept, cornell, {{"look-from", "0.2,1,3.5"}, {"look-at", "0,1,0"}});
}

TEST(loaded_scene, describes_the_asset_as_kiln_info_does) {
  loaded_scene kept(job_of(cornell, {}));
  kept.render(job_of(cornell, {}));
  for (const option_list& options : {option_list{}, {{"camera-view", "top"}, {"width", "64"}}}) {
    nlohmann::json ours = nlohmann::json::parse(asset_info_json(kept.describe(job_of(cornell, options))));
    nlohmann::json alone =
        nlohmann::json::parse(asset_info_json(describe_asset(job_of(cornell, options).options)));
    // The estimate's seconds come from timed probe renders; the rest is the asset's.
    for (nlohmann::json* j : {&ours, &alone})
      for (const char* timed : {"load_seconds", "render_seconds_one_thread", "peak_memory_bytes"})
        (*j)["render"].erase(timed);
    EXPECT_EQ(ours, alone);
    EXPECT_FALSE(ours["nodes"].empty());
  }
  expect_same_as_run_job(kept, cornell, {});  // and it still renders
}

TEST(loaded_scene, renders_from_two_threads_both_finish_as_run_job) {
  loaded_scene kept(job_of(cornell, {}));
  const option_list a = {{"look-from", "0.2,1,3.5"}, {"look-at", "0,1,0"}};
  const option_list b = {{"spp", "3"}, {"width", "30"}};
  std::vector<render_job_result> from_a, from_b;
  std::thread other([&] {
    for (int i = 0; i < 4; ++i) from_a.push_back(kept.render(job_of(cornell, a)));
  });
  for (int i = 0; i < 4; ++i) from_b.push_back(kept.render(job_of(cornell, b)));
  other.join();
  const render_job_result alone_a = run_job(job_of(cornell, a));
  const render_job_result alone_b = run_job(job_of(cornell, b));
  for (int i = 0; i < 4; ++i) {
    EXPECT_EQ(from_a[size_t(i)].image.color, alone_a.image.color) << i;
    EXPECT_EQ(from_b[size_t(i)].image.color, alone_b.image.color) << i;
  }
}

TEST(loaded_scene, each_render_gives_its_memory_back) {
  // One 320x320 render takes about 8.1 MiB of a 12 MiB budget (6.2 MiB of film); were the charges
  // kept, the second would be refused.
  const option_list big = {{"width", "320"}, {"height", "320"}, {"spp", "1"}, {"max-memory", "12M"}};
  loaded_scene kept(job_of(cornell, big));
  for (int i = 0; i < 3; ++i) EXPECT_EQ(kept.render(job_of(cornell, big)).image.width, 320);
}

}  // namespace
}  // namespace kiln
