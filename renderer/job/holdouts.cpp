#include "job/holdouts.h"

#include <fnmatch.h>

#include <sstream>
#include <vector>

#include "core/closest_name.h"
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

// The node forest as patterns see it: names (node<index> when unnamed, as Cryptomatte names
// objects), paths from the root ("/cornell_box/objects/blue_ball"), and which nodes place
// geometry in their subtree (only those can be selected).
struct node_tree {
  std::vector<int32_t> parents;
  std::vector<std::string> names;
  std::vector<std::string> paths;
  std::vector<bool> has_geometry;  // the node or a descendant places an instance
};

node_tree read_tree(const scene& world) {
  size_t count = std::max(world.node_names.size(), world.node_parents.size());
  for (const instance& inst : world.instances) count = std::max<size_t>(count, inst.node + size_t(1));
  node_tree t;
  t.parents.assign(count, -1);
  for (size_t n = 0; n < world.node_parents.size(); ++n)
    if (world.node_parents[n] >= 0 && size_t(world.node_parents[n]) < count)
      t.parents[n] = world.node_parents[n];
  for (size_t n = 0; n < count; ++n) {
    const std::string name = n < world.node_names.size() ? world.node_names[n] : std::string();
    t.names.push_back(name.empty() ? "node" + std::to_string(n) : name);
  }
  // The loader's validation leaves a forest; the step bound keeps a malformed one finite.
  t.paths.resize(count);
  for (size_t n = 0; n < count; ++n) {
    std::string path;
    size_t steps = 0;
    for (int32_t at = int32_t(n); at >= 0 && steps++ <= count; at = t.parents[size_t(at)])
      path = "/" + t.names[size_t(at)] + path;
    t.paths[n] = path;
  }
  t.has_geometry.assign(count, false);
  for (const instance& inst : world.instances) {
    size_t steps = 0;
    for (int32_t at = int32_t(inst.node); at >= 0 && !t.has_geometry[size_t(at)] && steps++ <= count;
         at = t.parents[size_t(at)])
      t.has_geometry[size_t(at)] = true;
  }
  return t;
}

bool is_glob(const std::string& pattern) { return pattern.find_first_of("*?[") != std::string::npos; }

// A pattern with a '/' is a path: from the root when it starts with '/', else any tail of the path
// ("objects/box" matches "/scene/objects/box"); `*` stays within one level. Else it is a name.
bool matches(const std::string& pattern, const node_tree& t, size_t node) {
  if (pattern.find('/') == std::string::npos) return fnmatch(pattern.c_str(), t.names[node].c_str(), 0) == 0;
  const std::string& path = t.paths[node];
  if (pattern.front() == '/') return fnmatch(pattern.c_str(), path.c_str(), FNM_PATHNAME) == 0;
  for (size_t slash = path.find('/'); slash != std::string::npos; slash = path.find('/', slash + 1))
    if (fnmatch(pattern.c_str(), path.c_str() + slash + 1, FNM_PATHNAME) == 0) return true;
  return false;
}

bool has_ancestor_in(const node_tree& t, size_t node, const std::vector<bool>& set) {
  size_t steps = 0;
  for (int32_t at = t.parents[node]; at >= 0 && steps++ <= t.parents.size(); at = t.parents[size_t(at)])
    if (set[size_t(at)]) return true;
  return false;
}

std::string listed(const std::vector<std::string>& items, size_t most) {
  std::string list;
  for (size_t i = 0; i < items.size(); ++i) {
    if (i == most) return list + ", ... " + std::to_string(items.size() - most) + " more";
    list += (list.empty() ? "" : ", ") + quoted(items[i]);
  }
  return list;
}

// "no node matches 'objcts'; did you mean 'objects'? (nodes: ...)", naming the nodes that hold or
// group geometry (by path when the pattern is one).
error no_match(const scene& world, const node_tree& t, const std::string& pattern,
               const std::string& option) {
  const bool by_path = pattern.find('/') != std::string::npos;
  std::vector<std::string> known;
  for (size_t n = 0; n < t.names.size(); ++n)
    if (t.has_geometry[n]) known.push_back(by_path ? t.paths[n] : t.names[n]);
  std::string reason = "no node with geometry matches " + quoted(pattern);
  // A path given from a node below the root ("/objects/box") suggests the full path it ends.
  std::optional<std::string> near;
  for (size_t n = 0; by_path && pattern.front() == '/' && !near && n < t.names.size(); ++n)
    if (t.has_geometry[n] && matches(pattern.substr(1), t, n)) near = t.paths[n];
  if (!near && !is_glob(pattern)) near = closest_name(pattern, known);
  if (near) reason += "; did you mean " + quoted(*near) + "?";
  return input_error(world.source, option, reason + " (nodes: " + listed(known, 8) + ")");
}

// The nodes each pattern selects: those it matches that hold or group geometry, less any whose
// ancestor it also matches. An exact name that selects two separate subtrees is ambiguous.
std::vector<bool> selected_nodes(const scene& world, const node_tree& t, const std::string& text,
                                 const std::string& option) {
  std::vector<bool> selected(t.names.size(), false);
  for (const std::string& pattern : split_patterns(text, option)) {
    std::vector<bool> hit(t.names.size(), false);
    bool any = false;
    for (size_t n = 0; n < t.names.size(); ++n)
      if (t.has_geometry[n] && matches(pattern, t, n)) hit[n] = any = true;
    if (!any) throw no_match(world, t, pattern, option);
    std::vector<std::string> outermost;
    for (size_t n = 0; n < t.names.size(); ++n)
      if (hit[n] && !has_ancestor_in(t, n, hit)) {
        selected[n] = true;
        outermost.push_back(t.paths[n]);
      }
    if (outermost.size() > 1 && !is_glob(pattern))
      throw input_error(world.source, option,
                        quoted(pattern) + " names " + std::to_string(outermost.size()) + " nodes (" +
                            listed(outermost, 8) + "); give the path of the one you mean, or a glob for all");
  }
  return selected;
}

// Per instance: whether its node or an ancestor of it is selected by text.
std::vector<bool> matched_instances(const scene& world, const node_tree& t, const std::string& text,
                                    const std::string& option) {
  const std::vector<bool> selected = selected_nodes(world, t, text, option);
  std::vector<bool> out(world.instances.size(), false);
  for (size_t i = 0; i < world.instances.size(); ++i) {
    const size_t node = world.instances[i].node;
    out[i] = selected[node] || has_ancestor_in(t, node, selected);
  }
  return out;
}

}  // namespace

void apply_holdouts(scene& world, const std::string& holdout, const std::string& only, holdout_kind others) {
  if (holdout.empty() && only.empty()) return;
  const node_tree tree = read_tree(world);
  const std::vector<bool> held = holdout.empty() ? std::vector<bool>(world.instances.size(), false)
                                                 : matched_instances(world, tree, holdout, "--holdout");
  const std::vector<bool> kept = only.empty() ? std::vector<bool>(world.instances.size(), true)
                                              : matched_instances(world, tree, only, "--only");
  for (size_t i = 0; i < world.instances.size(); ++i)
    if (held[i] || !kept[i]) world.instances[i].holdout = others;
}

holdout_kind others_kind(const std::string& others, bool holdout_invisible, bool deep) {
  if (others == "invisible" && holdout_invisible)
    throw input_error("", "--others",
                      "invisible (the camera passes the other nodes by) contradicts --holdout-invisible "
                      "(they matte the camera); give one of them");
  const bool unseen = others == "invisible" || (others == "auto" && deep && !holdout_invisible);
  if (unseen) return holdout_kind::unseen;
  return holdout_invisible ? holdout_kind::invisible : holdout_kind::matte;
}

}  // namespace kiln
