// The config scan against OpenColorIO's own reading: for every config OpenColorIO loads, the
// scan's count is at least the number of named entries OpenColorIO added (colour spaces, aliases,
// categories, named transforms, looks, view transforms, displays, views, roles, rules), whatever
// YAML style writes them; number vectors do not count; YAML that would defeat the count is refused.
#include "io/colour/module/ocio_config_text.h"

#include <OpenColorIO/OpenColorIO.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <random>
#include <sstream>

#include "io/colour/module/ocio_added_entries.h"

namespace kiln::colour_module {
namespace {

namespace OCIO = OCIO_NAMESPACE;

std::string shipped_config() {
  std::ifstream in(KILN_SOURCE_DIR "/share/ocio/kiln.ocio");
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

config_text_shape scan(const std::string& text) { return scan_config_text(text); }

TEST(ocio_config_text, counts_kilns_config_and_leaves_its_matrices_out) {
  const config_text_shape shape = scan(shipped_config());
  EXPECT_EQ(shape.refusal, "");
  EXPECT_EQ(shape.colour_spaces, 5u);
  std::istringstream in(shipped_config());
  const uint64_t added = ocio_added_entries(*OCIO::Config::CreateFromStream(in));
  EXPECT_GE(shape.entries, added);
  EXPECT_LE(shape.entries, 2 * added + 20);  // the top-level keys and lists such as active_views
}

TEST(ocio_config_text, every_style_of_list_counts) {
  const std::string head = "ocio_profile_version: 2\n";
  // Each count below starts with the config's top-level keys. Flow and block sequences, numbers
  // among the names.
  EXPECT_EQ(scan(head + "aliases: [a, 'b', \"c\", 1, 2]\n").entries, 2u + 5u);
  EXPECT_EQ(scan(head + "x:\n  - a\n  - 1\n  -\n  - [b]\n").entries, 2u + 4u + 1u);
  EXPECT_EQ(scan(head + "x:\n- a\n- b\ny: 1\n").entries, 3u + 2u);
  // A numeric key's vector of numbers is one vector, in either style; names under it are not.
  EXPECT_EQ(scan(head + "matrix: [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]\n").entries, 2u + 0u);
  EXPECT_EQ(scan(head + "t: {matrix: [1, .nan, -2e-3, .inf]}\n").entries, 2u + 1u + 0u);
  EXPECT_EQ(scan(head + "offset:\n  - 1\n  - 2.5\n").entries, 2u + 0u);
  EXPECT_EQ(scan(head + "matrix: [1, a]\n").entries, 2u + 2u);
  EXPECT_EQ(scan(head + "matrix:\n  - 1\n  - [2]\n").entries, 2u + 2u + 1u);
  // Pairs of the top two mapping levels (roles, displays), tagged or not, block or flow.
  EXPECT_EQ(scan(head + "roles:\n  a: x\n  'b': y\n").entries, 1u + 1u + 2u);
  EXPECT_EQ(scan(head + "roles: !<X> {a: x, b: y, c: z}\n").entries, 1u + 1u + 3u);
  EXPECT_EQ(scan(head + "displays: {d1: [], d2: []}\n").entries, 1u + 1u + 2u);
  EXPECT_EQ(scan("{ocio_profile_version: 2, roles: {a: x, b: y}}").entries, 2u + 2u);
  // Deeper mappings (a colour space's properties) do not count; their lists do.
  EXPECT_EQ(scan(head + "colorspaces:\n  - !<ColorSpace>\n    name: a\n    family: f\n    aliases: [b, c]\n"
                        "  - !<ColorSpace> {name: d, aliases: [e]}\n")
                .entries,
            1u + 1u + 2u + 2u + 1u);
  EXPECT_EQ(scan(head + "colorspaces:\n  - !<ColorSpace>\n    name: a\n  - !<ColorSpace>\n    name: b\n")
                .colour_spaces,
            2u);
}

TEST(ocio_config_text, scalars_comments_and_line_breaks_hide_nothing) {
  const std::string head = "ocio_profile_version: 2\n";
  // A block scalar ends where its indentation does; what follows counts.
  EXPECT_EQ(scan(head + "description: |\n  - a\n  - b\n    c: d\nx: [a, b]\n").entries, 1u + 1u + 1u + 2u);
  EXPECT_EQ(scan(head + "x:\n  - description: >-\n      text\n    y: [a]\n  - b\n").entries,
            1u + 1u + 2u + 1u);
  // Quoted scalars over several lines, with escapes and brackets inside.
  EXPECT_EQ(scan(head + "d: \"a [b,\n  c] \\\" d\"\nx: [a]\n").entries, 1u + 1u + 1u + 1u);
  EXPECT_EQ(scan(head + "d: 'it''s [x, y'\nx: [a]\n").entries, 1u + 1u + 1u + 1u);
  // Comments; a '#' inside a scalar is not one.
  EXPECT_EQ(scan(head + "x: [a, # b, c\n  d]\ny: a#b\n").entries, 1u + 1u + 2u + 1u);
  // CR LF breaks lines; a lone CR is text to yaml-cpp, as it is here.
  EXPECT_EQ(scan("ocio_profile_version: 2\r\nx:\r\n  - a\r\n  - b\r\n").entries, 1u + 1u + 2u);
  EXPECT_EQ(scan("ocio_profile_version: 2\rx:\r  - a\r  - b\r").entries, 1u);
  // Only the first document is read, as yaml-cpp reads it.
  EXPECT_EQ(scan(head + "x: [a]\n---\ny: [a, b, c]\n").entries, 1u + 1u + 1u);
  EXPECT_EQ(scan("# c\n%YAML 1.2\n---\n" + head + "x: [a]\n").entries, 1u + 1u + 1u);
}

// Configs whose every alias a scan that ended a scalar or a tag elsewhere than yaml-cpp does
// would miss: OpenColorIO loads each, and the count holds what it added.
TEST(ocio_config_text, scalars_and_tags_end_where_yaml_cpp_ends_them) {
  std::string aliases = "[a0";
  for (int i = 1; i < 50; ++i) aliases += ", a" + std::to_string(i);
  const std::string head =
      "ocio_profile_version: 2\nroles:\n  default: s0\ndisplays:\n  d: [!<View> {name: v, colorspace: s0}]\n";
  const std::string spaces = "colorspaces: [!<ColorSpace> {name: s0, aliases: " + aliases + "]}]\n";
  OCIO::SetLoggingLevel(OCIO::LOGGING_LEVEL_NONE);  // the configs' unknown keys x, y and z
  for (const std::string& yaml : {
           // A tag ends at a '"', which opens a scalar that closes on the same line.
           head + "x: !a\"abc 'zzz\"\n" + spaces + "y: 'q'\n",
           // A plain scalar goes on over a more indented line, quote and all.
           head + "description: x\n  'hidden\n" + spaces + "z: 'q'\n",
           // At a token's start, '#' is a comment even after a comma.
           head + "colorspaces: [!<ColorSpace> {name: s0, aliases: [a,#b, c\n" + aliases.substr(1) + "]}]\n",
       }) {
    std::istringstream in(yaml);
    const OCIO::ConstConfigRcPtr cfg = OCIO::Config::CreateFromStream(in);
    EXPECT_GE(cfg->getColorSpace("s0")->getNumAliases(), 50) << yaml;
    const config_text_shape shape = scan(yaml);
    EXPECT_EQ(shape.refusal, "");
    EXPECT_GE(shape.entries, ocio_added_entries(*cfg)) << yaml;
  }
  // A block scalar's first lines set its indentation, empty ones included: the scalar below is
  // empty, and the line after it is a key (yaml-cpp refuses the document; so does OpenColorIO).
  EXPECT_EQ(scan("ocio_profile_version: 2\ndescription: |\n        \n  x: [a, b]\n").entries, 2u + 1u + 2u);
}

TEST(ocio_config_text, yaml_that_would_defeat_the_count_is_refused) {
  const std::string head = "ocio_profile_version: 2\n";
  EXPECT_EQ(scan(head + "x: &list [a, b]\ny: *list\n").refusal, "line 2 has a YAML anchor (&)");
  EXPECT_EQ(scan(head + "x: [a, *b]\n").refusal, "line 2 has a YAML alias (*)");
  EXPECT_EQ(scan("%TAG !e! tag:x,2000:\n---\n" + head).refusal, "line 1 has a %TAG directive");
  EXPECT_EQ(scan(head + "? x\n: y\n").refusal, "line 2 has an explicit key (?)");
  EXPECT_EQ(scan(head + "x:\n\t- a\n").refusal,
            "line 3 has a tab in its indentation (YAML indents with spaces)");
  // Not at a node's start, these characters are text.
  EXPECT_EQ(scan(head + "description: R&D *draft* 100%\nfile_rules:\n  - !<Rule> {pattern: \"*\"}\n").refusal,
            "");
  EXPECT_EQ(scan(head + "x: a\t# a tab before a comment\n").refusal, "");
}

// A config of `bytes` colour spaces' text, then as many open brackets, never closed, as it has
// bytes over four.
std::string long_config(size_t bytes) {
  std::string big = "ocio_profile_version: 2\ncolorspaces:\n";
  while (big.size() < bytes)
    big += "  - !<ColorSpace>\n    name: s" + std::to_string(big.size()) +
           "\n    to_scene_reference: !<MatrixTransform> {matrix: [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, "
           "0, 1]}\n";
  return big + "x: [" + std::string(bytes / 4, '[') + "\n";
}

// The fastest of three scans, in seconds.
double scan_seconds(const std::string& text) {
  double best = 1e9;
  for (int i = 0; i < 3; ++i) {
    const auto start = std::chrono::steady_clock::now();
    scan(text);
    best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  return best;
}

// Four times the text takes about four times as long (a quadratic scan: sixteen). A ratio, not a
// time, so a loaded machine or a sanitizer build slows both sides alike.
TEST(ocio_config_text, the_scan_is_linear_in_the_text) {
  const std::string small = long_config(size_t(1) << 20), big = long_config(size_t(4) << 20);
  EXPECT_GT(scan(big).colour_spaces, 30000u);
  const double ratio = scan_seconds(big) / scan_seconds(small);
  std::printf("4x the text: %.2fx the time\n", ratio);
  EXPECT_LT(ratio, 9.0);
}

// One randomly written config: lists of every kind, each in block or flow style, names plain,
// quoted or numeric, comments and descriptions between them.
std::string random_config(std::mt19937& rng) {
  auto pick = [&rng](int n) { return int(rng() % uint32_t(n)); };
  int next = 0;
  auto name = [&]() {
    const std::string n = std::to_string(next++);
    switch (pick(3)) {
      case 0:
        return "n" + n;
      case 1:
        return "'q " + n + "'";
      default:
        return n;  // a number as a name
    }
  };
  // A list of count names under key, at indent (block) or inline (flow).
  auto list = [&](const std::string& key, int count, const std::string& indent) {
    std::string out = indent + key + ":";
    if (pick(2)) {
      out += " [";
      for (int i = 0; i < count; ++i) out += (i ? ", " : "") + name();
      return out + "]\n";
    }
    out += count ? "\n" : " []\n";
    for (int i = 0; i < count; ++i) out += indent + (pick(2) ? "  " : "") + "- " + name() + "\n";
    return out;
  };
  std::string y = "ocio_profile_version: 2\nsearch_path: \".\"\n";
  if (pick(2)) y += "description: |\n  - a: b\n  - [c, d]\n";
  y += "roles:\n  default: s0\n  scene_linear: s0\n";
  for (int i = pick(6); i > 0; --i) y += "  r" + std::to_string(next++) + ": s0\n";
  y += "displays:\n";
  const int displays = 1 + pick(4);
  for (int d = 0; d < displays; ++d) {
    y += "  d" + std::to_string(next++) + ":\n";
    for (int v = pick(4) + 1; v > 0; --v)
      y += "    - !<View> {name: v" + std::to_string(next++) + ", colorspace: s0}\n";
  }
  y += "# a comment\nlooks:\n";
  for (int i = pick(4); i > 0; --i)
    y += "  - !<Look> {name: l" + std::to_string(next++) + ", process_space: s0}\n";
  if (y.back() == ':' || y.compare(y.size() - 7, 7, "looks:\n") == 0) y += "  []\n";
  y += "colorspaces:\n";
  for (int i = 0; i < 1 + pick(6); ++i) {
    const bool flow = pick(2);
    const std::string cs = i == 0 ? "s0" : "s" + std::to_string(next++);
    if (flow) {
      y += "  - !<ColorSpace> {name: " + cs + ", aliases: [";
      for (int a = pick(5); a > 0; --a) y += "a" + std::to_string(next++) + (a > 1 ? ", " : "");
      y += "], to_scene_reference: !<MatrixTransform> {offset: [0, 0, 0, 0]}}\n";
    } else {
      y += "  - !<ColorSpace>\n    name: " + cs + "\n";
      y += list("aliases", pick(5), "    ");
      y += list("categories", pick(3), "    ");
      y += "    description: \"multi-line\n      [x, y]\"\n";
    }
  }
  y += "named_transforms:\n";
  for (int i = pick(4); i > 0; --i)
    y += "  - !<NamedTransform>\n    name: t" + std::to_string(next++) +
         "\n    transform: !<MatrixTransform> {}\n" + list("aliases", pick(3), "    ");
  if (y.compare(y.size() - 18, 18, "named_transforms:\n") == 0) y += "  []\n";
  return y;
}

TEST(ocio_config_text, the_count_holds_what_opencolorio_adds_for_random_configs) {
  std::mt19937 rng(43);
  int loaded = 0;
  for (int round = 0; round < 300; ++round) {
    const std::string yaml = random_config(rng);
    OCIO::ConstConfigRcPtr cfg;
    try {
      std::istringstream in(yaml);
      cfg = OCIO::Config::CreateFromStream(in);
    } catch (const OCIO::Exception&) {
      continue;  // names that clash: OpenColorIO refuses the config anyway
    }
    ++loaded;
    const config_text_shape shape = scan(yaml);
    ASSERT_EQ(shape.refusal, "") << yaml;
    EXPECT_GE(shape.entries, ocio_added_entries(*cfg)) << yaml;
  }
  EXPECT_GT(loaded, 200);
}

}  // namespace
}  // namespace kiln::colour_module
