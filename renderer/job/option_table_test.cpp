// The option table against itself and against what it feeds: every option that changes pixels
// reaches the settings hash and the region ones only the band's, every value reads back through
// its own parser, bad text is refused in the option's name, and the docs' option tables explain
// exactly the table's options, each once. Adding an entry that misses any of these fails here,
// with its name.
#include "job/option_table.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>

#include "core/error.h"
#include "job/memory_limit.h"
#include "job/option_values.h"
#include "job/render_fingerprint.h"

namespace kiln {
namespace {

namespace fs = std::filesystem;

// The example of an entry, with the one that names a file pointed at a file that exists.
std::string example_of(const option_spec& spec) {
  static const std::string sky = KILN_SOURCE_DIR "/scenes/glass_showcase_sky.hdr";
  static const std::string config = KILN_SOURCE_DIR "/share/ocio/kiln.ocio";
  if (spec.name == "environment") return sky;
  if (spec.name == "ocio-config") return config;
  return spec.example;
}

TEST(option_table, names_are_unique_and_every_entry_is_complete) {
  std::set<std::string> names;
  for (const option_spec& spec : render_option_table()) {
    EXPECT_TRUE(names.insert(spec.name).second) << spec.name << " is declared twice";
    if (!spec.alias.empty()) {
      EXPECT_TRUE(names.insert(spec.alias).second) << spec.alias;
    }
    EXPECT_FALSE(spec.help.empty()) << spec.name;
    EXPECT_TRUE(spec.set && spec.get) << spec.name;
    EXPECT_FALSE(example_of(spec).empty()) << spec.name << " has no example value";
  }
  EXPECT_GE(names.size(), 55u);
}

TEST(option_table, every_option_is_in_a_group_and_every_group_has_options) {
  std::map<option_group, int> count;
  for (const option_spec& spec : render_option_table()) {
    EXPECT_NE(spec.group, option_group::unassigned) << spec.name << " has no group";
    ++count[spec.group];
  }
  std::set<std::string> titles;
  for (option_group group : option_groups()) {
    EXPECT_GT(count[group], 0) << option_group_title(group) << " holds no option";
    EXPECT_TRUE(titles.insert(option_group_title(group)).second) << option_group_title(group);
  }
  EXPECT_EQ(option_groups().front(), option_group::output);
  EXPECT_EQ(option_groups().back(), option_group::limits);
  EXPECT_EQ(find_render_option("spp")->group, option_group::sampling);
  EXPECT_EQ(find_render_option("max-nodes")->group, option_group::limits);
  // The paths a shell completes as files.
  EXPECT_TRUE(find_render_option("environment")->names_file);
  EXPECT_TRUE(find_render_option("preview")->names_file);
  EXPECT_FALSE(find_render_option("camera")->names_file);
}

TEST(option_table, every_option_that_changes_pixels_reaches_the_settings_hash) {
  const render_options base;
  const render_fingerprint reference = make_fingerprint(base);
  for (const option_spec& spec : render_option_table()) {
    render_options changed = base;
    ASSERT_NO_THROW(spec.set(changed, example_of(spec))) << spec.name;
    EXPECT_NE(spec.get(changed), spec.get(base)) << spec.name << ": its example is its default";
    const render_fingerprint f = make_fingerprint(changed);
    switch (spec.effect) {
      case option_effect::pixels:
        EXPECT_NE(f.settings_hash, reference.settings_hash)
            << spec.name << " does not reach the settings hash";
        EXPECT_NE(f.frame_settings_hash, reference.frame_settings_hash) << spec.name;
        break;
      case option_effect::region:
        EXPECT_NE(f.settings_hash, reference.settings_hash) << spec.name;
        EXPECT_EQ(f.frame_settings_hash, reference.frame_settings_hash)
            << spec.name << " changes the frame's hash";
        break;
      case option_effect::none:
        EXPECT_EQ(f.settings_hash, reference.settings_hash)
            << spec.name << " has no effect but changes the hash";
        break;
    }
  }
}

TEST(option_table, canonical_arguments_read_back_to_the_same_options) {
  render_options o;
  for (const option_spec& spec : render_option_table())
    if (spec.effect != option_effect::none && spec.name != "crop") spec.set(o, example_of(spec));
  o.filter_radius = 1.2345678f;  // digits a short printout would lose
  o.fov_degrees = 33.333333333333336;
  o.look_from = dvec3(0.1, -2.5, 1e-7);
  const std::vector<std::string> args = canonical_render_arguments(o, region_arguments::include);
  render_options parsed;
  for (size_t i = 0; i < args.size(); ++i) {
    const option_spec* spec = find_render_option(args[i]);
    ASSERT_NE(spec, nullptr) << args[i];
    const bool flag = spec->type == option_type::flag;
    spec->set(parsed, flag ? "true" : args.at(++i));
  }
  EXPECT_EQ(canonical_render_arguments(parsed, region_arguments::include), args);
  EXPECT_EQ(make_fingerprint(parsed).settings_hash, make_fingerprint(o).settings_hash);
  EXPECT_EQ(parsed.filter_radius, o.filter_radius);
  EXPECT_EQ(parsed.fov_degrees, o.fov_degrees);
  EXPECT_EQ(parsed.look_from, o.look_from);
  EXPECT_EQ(parsed.band_count, 4);
  // Without the region the same settings lack only --band.
  const std::vector<std::string> without = canonical_render_arguments(o, region_arguments::omit);
  EXPECT_EQ(without.size() + 2, args.size());
  EXPECT_EQ(std::find(without.begin(), without.end(), "--band"), without.end());
}

TEST(option_table, bad_text_is_refused_in_the_options_name) {
  for (const option_spec& spec : render_option_table()) {
    if (spec.type == option_type::text && spec.choices.empty()) continue;  // any text may be a name
    render_options o;
    try {
      spec.set(o, "not-a-value");
      ADD_FAILURE() << spec.name << " accepted 'not-a-value'";
    } catch (const error& e) {
      EXPECT_EQ(e.kind(), error_kind::input) << spec.name;
      EXPECT_EQ(e.location(), "--" + spec.name);
      EXPECT_NE(e.reason().find("'not-a-value'"), std::string::npos) << e.what();
    }
  }
  render_options o;
  EXPECT_THROW(set_render_option(o, "spp", "nan"), error);
  EXPECT_THROW(set_render_option(o, "fov", "nan"), error);
  EXPECT_THROW(set_render_option(o, "max-nodes", "-3"), error);
  EXPECT_THROW(set_render_option(o, "no-such-option", "1"), error);
  set_render_option(o, "--tile", "2/3");  // the deprecated name of --band
  EXPECT_EQ(o.band_index, 2);
  set_render_option(o, "q", "true");
  EXPECT_TRUE(o.quiet);
}

TEST(option_table, recorded_options_are_the_exr_attributes) {
  render_options o;
  o.spp_given = 4;
  o.embree.compact = true;
  set_render_option(o, "time", "0.1");
  set_render_option(o, "shutter", "-0.25,0.5");
  set_render_option(o, "background", "0.5,0.25,2");
  set_render_option(o, "environment-intensity", "1.5");
  std::map<std::string, exr_value> attributes;
  for (const auto& [key, value] : recorded_option_attributes(o)) attributes[key] = value;
  // Numbers are stored as numbers, of the type the value has; the rest as text.
  EXPECT_EQ(attributes["kiln/samples_per_pixel"], exr_value(4));
  EXPECT_EQ(attributes["kiln/max_depth"], exr_value(o.max_depth));
  EXPECT_EQ(attributes["kiln/time"], exr_value(0.1));  // a double: the pose's time exactly
  EXPECT_EQ(attributes["kiln/environment_intensity"], exr_value(1.5f));
  EXPECT_EQ(attributes["kiln/shutter"], exr_value(vec2(-0.25f, 0.5f)));
  EXPECT_EQ(attributes["kiln/background"], exr_value(vec3(0.5f, 0.25f, 2.0f)));
  EXPECT_EQ(attributes["kiln/bvh_compact"], exr_value("on"));
  EXPECT_EQ(attributes["kiln/packets"], exr_value("on"));
  EXPECT_EQ(attributes["kiln/aovs"], exr_value("beauty,Z,N"));
  EXPECT_EQ(attributes["kiln/accelerator"], exr_value("embree"));
  EXPECT_EQ(attributes.count("kiln/frame"), 0u);  // not given: not recorded
}

// The docs' render option tables (docs/*.md, each table whose header is `| render option | meaning |`):
// their first column's `--name`s, each with the page that explains it.
std::multimap<std::string, std::string> documented_render_options() {
  std::multimap<std::string, std::string> names;
  const std::regex option(R"(--([a-z][a-z-]*))");
  for (const auto& entry : std::filesystem::directory_iterator(KILN_SOURCE_DIR "/docs")) {
    if (entry.path().extension() != ".md") continue;
    std::ifstream in(entry.path());
    bool in_table = false;
    for (std::string line; std::getline(in, line);) {
      if (line.rfind("|", 0) != 0) in_table = false;  // a table ends at its first line without a cell
      if (line == "| render option | meaning |") in_table = true;
      if (!in_table || line.rfind("| `--", 0) != 0) continue;
      const std::string first = line.substr(0, line.find(" | "));
      for (std::sregex_iterator m(first.begin(), first.end(), option), end; m != end; ++m)
        names.emplace((*m)[1], entry.path().filename().string());
    }
  }
  return names;
}

TEST(option_table, the_docs_explain_every_option_once) {
  const std::multimap<std::string, std::string> listed = documented_render_options();
  ASSERT_GE(listed.size(), 40u);
  std::set<std::string> table;
  for (const option_spec& spec : render_option_table()) {
    table.insert(spec.name);
    if (spec.name != "quiet") {
      EXPECT_EQ(listed.count(spec.name), 1u)
          << "docs/*.md explain --" << spec.name << " " << listed.count(spec.name) << " times";
    }
  }
  for (const auto& [name, page] : listed)
    EXPECT_EQ(table.count(name), 1u) << "docs/" << page << " lists --" << name;
}

}  // namespace
}  // namespace kiln

namespace kiln {
namespace {

TEST(MemorySizes, BytesAndBinaryUnits) {
  EXPECT_EQ(parse_memory_size("512", "--max-memory"), 512u);
  EXPECT_EQ(parse_memory_size("4G", "--max-memory"), uint64_t(4) << 30);
  EXPECT_EQ(parse_memory_size("3m", "--max-memory"), uint64_t(3) << 20);
  EXPECT_EQ(parse_memory_size("2KiB", "--max-memory"), 2048u);
  EXPECT_EQ(parse_memory_size("1T", "--max-memory"), uint64_t(1) << 40);
  for (const char* bad : {"", "G", "1.5G", "0", "4X", "4GG", "99999999999T"})
    EXPECT_THROW(parse_memory_size(bad, "--max-memory"), error) << bad;
}

TEST(MemorySizes, CgroupLimitFiles) {
  EXPECT_EQ(parse_cgroup_limit("max\n"), 0u);
  EXPECT_EQ(parse_cgroup_limit("4294967296\n"), uint64_t(4) << 30);
  EXPECT_EQ(parse_cgroup_limit("9223372036854771712\n"), 0u);  // v1's "no limit"
  EXPECT_EQ(parse_cgroup_limit(""), 0u);
  EXPECT_GT(default_memory_budget(), 0u);
}

}  // namespace
}  // namespace kiln
