#include "job/holdouts.h"

#include <fnmatch.h>

#include <set>
#include <sstream>
#include <vector>

#include "core/error.h"
#include "core/message_text.h"

namespace kiln {

namespace {

std::vector<std::string> split_patterns(const std::string& text, const std::string& option) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string item; std::getline(in, item, ',');) {
    if (item.empty()) throw input_error("", option, "expects node names or globs separated by commas");
    out.push_back(item);
  }
  if (!text.empty() && text.back() == ',')
    throw input_error("", option, "expects node names or globs separated by commas");
  return out;
}

std::string node_name(const scene& world, uint32_t node) {
  const std::string& name = node < world.node_names.size() ? world.node_names[node] : std::string();
  return name.empty() ? "node" + std::to_string(node) : name;
}

bool matches(const std::string& pattern, const std::string& name) {
  return fnmatch(pattern.c_str(), name.c_str(), 0) == 0;
}

// For each pattern, whether the instance's node matches; throws for a pattern no instance matches.
std::vector<bool> matched_instances(const scene& world, const std::string& text, const std::string& option) {
  std::vector<bool> hit(world.instances.size(), false);
  for (const std::string& pattern : split_patterns(text, option)) {
    bool any = false;
    for (size_t i = 0; i < world.instances.size(); ++i)
      if (matches(pattern, node_name(world, world.instances[i].node))) hit[i] = any = true;
    if (any) continue;
    std::set<std::string> names;
    for (const instance& inst : world.instances) names.insert(node_name(world, inst.node));
    std::string list;
    size_t listed = 0;
    for (const std::string& n : names) {
      if (listed++ == 8) {
        list += ", ... " + std::to_string(names.size() - 8) + " more";
        break;
      }
      list += (list.empty() ? "" : ", ") + quoted(n);
    }
    throw input_error(world.source, option,
                      "no node with geometry matches " + quoted(pattern) + " (nodes: " + list + ")");
  }
  return hit;
}

}  // namespace

void apply_holdouts(scene& world, const std::string& holdout, const std::string& only, bool invisible) {
  if (holdout.empty() && only.empty()) return;
  const std::vector<bool> held = holdout.empty() ? std::vector<bool>(world.instances.size(), false)
                                                 : matched_instances(world, holdout, "--holdout");
  const std::vector<bool> kept = only.empty() ? std::vector<bool>(world.instances.size(), true)
                                              : matched_instances(world, only, "--only");
  const holdout_kind kind = invisible ? holdout_kind::invisible : holdout_kind::matte;
  for (size_t i = 0; i < world.instances.size(); ++i)
    if (held[i] || !kept[i]) world.instances[i].holdout = kind;
}

}  // namespace kiln
