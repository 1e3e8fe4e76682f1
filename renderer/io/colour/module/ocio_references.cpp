// OpenColorIO 2.1 builds a processor by following every name a transform holds (a
// ColorSpaceTransform's src and dst, a look list, a display/view) into that object's transforms,
// recursively, without a guard and without memoising (its context-variable scan in
// Config::getProcessor follows both directions of every colour space it meets). So this walk
// follows the same references, as a graph of named objects, and bounds what OpenColorIO would do.
#include "io/colour/module/ocio_references.h"

#include <algorithm>
#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "core/error.h"
#include "core/message_text.h"

namespace OCIO = OCIO_NAMESPACE;

namespace kiln::colour_module {
namespace {

// References and GroupTransforms nested, each a level of OpenColorIO's recursion: a chain of 5000
// colour spaces, each converting through the next inside a group, overflows an 8 MiB stack;
// kiln's own config nests 3 deep (a conversion, a colour space, a group), studio configs a few more.
constexpr int max_depth = 100;
// OpenColorIO walks a shared reference once for every path that reaches it: 2^20 walks take it
// 4 s, per processor. Real configs make a few dozen.
constexpr uint64_t max_walk = 100000;

enum class object_kind { colour_space, named_transform, look, view_transform };

// A config object that transforms can name.
struct config_object {
  object_kind kind = object_kind::colour_space;
  std::string name;  // the config's own name (an alias or role resolved)
};

// Unique per object (a quoted name is cut at max_shown_bytes, so two long names could meet).
std::string key(const config_object& o) { return char('0' + int(o.kind)) + o.name; }

std::string describe(const config_object& o) {
  static const char* const kinds[] = {"colour space", "named transform", "look", "view transform"};
  return std::string(kinds[int(o.kind)]) + " " + quoted(o.name);
}

// One object naming another: where in the first the name is written (for messages), and inside
// how many GroupTransforms (OpenColorIO recurses through those too).
struct reference {
  config_object target;
  std::string where;
  int nesting = 0;
};

// Field by field: GCC 12 takes a braced nested aggregate for a maybe-uninitialised string.
void add(std::vector<reference>& out, object_kind kind, const char* name, const std::string& where,
         int nesting) {
  reference r;
  r.target.kind = kind;
  r.target.name = name;
  r.where = where;
  r.nesting = nesting;
  out.push_back(std::move(r));
}

// The references of one object, found through the config's API (nothing here builds a processor).
// Both directions of every transform and every option of a look list count, as OpenColorIO's
// scan counts them; a name the config does not have is left to OpenColorIO to report.
class reference_finder {
 public:
  explicit reference_finder(const OCIO::Config& cfg) : cfg_(cfg), context_(cfg.getCurrentContext()) {}

  std::vector<reference> operator()(const config_object& o) const {
    std::vector<reference> out;
    for (const auto& [where, t] : transforms_of(o)) transform(t, where, 0, out);
    switch (o.kind) {
      case object_kind::colour_space:
        // A conversion between the two reference spaces goes through the default view transform.
        if (cfg_.getColorSpace(o.name.c_str())->getReferenceSpaceType() == OCIO::REFERENCE_SPACE_DISPLAY)
          if (const OCIO::ConstViewTransformRcPtr vt = cfg_.getDefaultSceneToDisplayViewTransform())
            add(out, object_kind::view_transform, vt->getName(),
                "display reference: the default view transform", 0);
        break;
      case object_kind::look:
        named(cfg_.getLook(o.name.c_str())->getProcessSpace(), "process_space", 0, out);
        break;
      case object_kind::named_transform:
      case object_kind::view_transform:
        break;
    }
    return out;
  }

  // The transforms o holds, each with the key it is written under (null ones left out).
  std::vector<std::pair<std::string, OCIO::ConstTransformRcPtr>> transforms_of(const config_object& o) const {
    std::vector<std::pair<std::string, OCIO::ConstTransformRcPtr>> out;
    auto keep = [&out](const char* where, const OCIO::ConstTransformRcPtr& t) {
      if (t) out.emplace_back(where, t);
    };
    switch (o.kind) {
      case object_kind::colour_space: {
        const OCIO::ConstColorSpaceRcPtr cs = cfg_.getColorSpace(o.name.c_str());
        const bool scene = cs->getReferenceSpaceType() == OCIO::REFERENCE_SPACE_SCENE;
        keep(scene ? "to_scene_reference" : "to_display_reference",
             cs->getTransform(OCIO::COLORSPACE_DIR_TO_REFERENCE));
        keep(scene ? "from_scene_reference" : "from_display_reference",
             cs->getTransform(OCIO::COLORSPACE_DIR_FROM_REFERENCE));
        break;
      }
      case object_kind::named_transform: {
        const OCIO::ConstNamedTransformRcPtr nt = cfg_.getNamedTransform(o.name.c_str());
        keep("transform", nt->getTransform(OCIO::TRANSFORM_DIR_FORWARD));
        keep("inverse_transform", nt->getTransform(OCIO::TRANSFORM_DIR_INVERSE));
        break;
      }
      case object_kind::look: {
        const OCIO::ConstLookRcPtr lk = cfg_.getLook(o.name.c_str());
        keep("transform", lk->getTransform());
        keep("inverse_transform", lk->getInverseTransform());
        break;
      }
      case object_kind::view_transform: {
        const OCIO::ConstViewTransformRcPtr vt = cfg_.getViewTransform(o.name.c_str());
        const bool scene = vt->getReferenceSpaceType() == OCIO::REFERENCE_SPACE_SCENE;
        keep(scene ? "to_scene_reference" : "to_display_reference",
             vt->getTransform(OCIO::VIEWTRANSFORM_DIR_TO_REFERENCE));
        keep(scene ? "from_scene_reference" : "from_display_reference",
             vt->getTransform(OCIO::VIEWTRANSFORM_DIR_FROM_REFERENCE));
        break;
      }
    }
    return out;
  }

  // The references of a transform kiln builds (a ColorSpaceTransform, a DisplayViewTransform...).
  std::vector<reference> operator()(const OCIO::ConstTransformRcPtr& conversion) const {
    std::vector<reference> out;
    transform(conversion, "kiln's conversion", 0, out);
    return out;
  }

 private:
  // The transforms that name other objects; the rest (matrices, curves, files) name none.
  void transform(const OCIO::ConstTransformRcPtr& t, const std::string& where, int nesting,
                 std::vector<reference>& out) const {
    if (const auto group = OCIO::DynamicPtrCast<const OCIO::GroupTransform>(t)) {
      for (int i = 0; i < group->getNumTransforms(); ++i)
        transform(group->getTransform(i), where, nesting + 1, out);
    } else if (const auto cst = OCIO::DynamicPtrCast<const OCIO::ColorSpaceTransform>(t)) {
      named(cst->getSrc(), where + ": ColorSpaceTransform src", nesting, out);
      named(cst->getDst(), where + ": ColorSpaceTransform dst", nesting, out);
    } else if (const auto lt = OCIO::DynamicPtrCast<const OCIO::LookTransform>(t)) {
      named(lt->getSrc(), where + ": LookTransform src", nesting, out);
      named(lt->getDst(), where + ": LookTransform dst", nesting, out);
      looks(lt->getLooks(), where + ": LookTransform looks", nesting, out);
    } else if (const auto dvt = OCIO::DynamicPtrCast<const OCIO::DisplayViewTransform>(t)) {
      named(dvt->getSrc(), where + ": DisplayViewTransform src", nesting, out);
      display_view(*dvt, where + ": DisplayViewTransform view", nesting, out);
    }
  }

  // A colour space (or role, or alias) or a named transform, as ColorSpaceTransform resolves it.
  void named(const char* name, const std::string& where, int nesting, std::vector<reference>& out) const {
    if (!name || !*name) return;
    const char* resolved = context_->resolveStringVar(name);
    if (const OCIO::ConstColorSpaceRcPtr cs = cfg_.getColorSpace(resolved))
      add(out, object_kind::colour_space, cs->getName(), where, nesting);
    else if (const OCIO::ConstNamedTransformRcPtr nt = cfg_.getNamedTransform(resolved))
      add(out, object_kind::named_transform, nt->getName(), where, nesting);
  }

  // "grade, +film look | -neutral": every look of every option, whatever its direction (names may
  // hold spaces and dashes; a leading + or - is the direction), as OpenColorIO parses the list.
  void looks(const char* list, const std::string& where, int nesting, std::vector<reference>& out) const {
    const std::string text = list ? list : "";
    const char* const blank = " \t";
    size_t begin = 0;
    while (begin <= text.size()) {
      const size_t end = std::min(text.find_first_of(",:|", begin), text.size());
      std::string name = text.substr(begin, end - begin);
      name.erase(0, name.find_first_not_of(blank));
      if (!name.empty() && (name[0] == '+' || name[0] == '-')) name.erase(0, 1);
      name.erase(0, name.find_first_not_of(blank));
      name.erase(name.find_last_not_of(blank) + 1);
      if (const OCIO::ConstLookRcPtr lk = name.empty() ? nullptr : cfg_.getLook(name.c_str()))
        add(out, object_kind::look, lk->getName(), where, nesting);
      begin = end + 1;
    }
  }

  // A display/view: its colour space, its view transform and its looks.
  void display_view(const OCIO::DisplayViewTransform& dvt, const std::string& where, int nesting,
                    std::vector<reference>& out) const {
    std::string space = cfg_.getDisplayViewColorSpaceName(dvt.getDisplay(), dvt.getView());
    if (space == OCIO::OCIO_VIEW_USE_DISPLAY_NAME) space = dvt.getDisplay();
    named(space.c_str(), where, nesting, out);
    const char* vt_name = cfg_.getDisplayViewTransformName(dvt.getDisplay(), dvt.getView());
    if (const OCIO::ConstViewTransformRcPtr vt =
            vt_name && *vt_name ? cfg_.getViewTransform(vt_name) : nullptr)
      add(out, object_kind::view_transform, vt->getName(), where, nesting);
    if (!dvt.getLooksBypass())
      looks(cfg_.getDisplayViewLooks(dvt.getDisplay(), dvt.getView()), where, nesting, out);
  }

  const OCIO::Config& cfg_;
  OCIO::ConstContextRcPtr context_;
};

// What the walk from a finished object found: the deepest nesting below it and how many
// references OpenColorIO would follow from it (capped just past max_walk).
struct walk_extent {
  int depth = 0;
  uint64_t references = 0;
};

// Depth-first over the objects, each finished once; the chain of objects being walked finds loops.
class reference_walk {
 public:
  reference_walk(const OCIO::Config& cfg, const colour_config_source& config) : find_(cfg), config_(config) {}

  // o, reached through `level` references and groups from kiln's conversion.
  walk_extent visit(const config_object& o, int level) {
    const std::string name = key(o);
    if (const auto done = finished_.find(name); done != finished_.end()) {
      if (level + done->second.depth > max_depth)
        throw too_deep(o, " [" + std::to_string(done->second.depth) + " more levels below]");
      return done->second;
    }
    for (size_t i = 0; i < chain_.size(); ++i)
      if (key(chain_[i].first) == name)
        throw refused(describe(chain_[i].first), "its references loop back to it (" + chain_text(i, o) + ")");
    // Also bounds this walk's own recursion.
    if (level > max_depth) throw too_deep(o, "");
    chain_.emplace_back(o, "");
    const walk_extent extent = below(find_(o), level);
    chain_.pop_back();
    if (extent.references > max_walk)
      throw refused(describe(o),
                    "its references branch into more than " + std::to_string(max_walk) + " paths");
    finished_.emplace(name, extent);
    reached_.push_back(o);
    return extent;
  }

  void check_conversion(const OCIO::ConstTransformRcPtr& conversion) {
    if (below(find_(conversion), 0).references > max_walk)
      throw refused("kiln's conversion",
                    "the references it reaches branch into more than " + std::to_string(max_walk) + " paths");
  }

  // The transforms of every object the walk reached, in the order it finished them.
  std::vector<held_transform> held() const {
    std::vector<held_transform> out;
    for (const config_object& o : reached_)
      for (const auto& [where, t] : find_.transforms_of(o))
        out.push_back({t, describe(o) + " [" + where + "]"});
    return out;
  }

 private:
  // The extent of the last object on the chain (or of kiln's conversion, at level 0) with these
  // references.
  walk_extent below(const std::vector<reference>& references, int level) {
    walk_extent extent;
    for (const reference& r : references) {
      if (!chain_.empty()) chain_.back().second = r.where;
      const walk_extent next = visit(r.target, level + 1 + r.nesting);
      extent.depth = std::max(extent.depth, 1 + r.nesting + next.depth);
      extent.references = std::min(max_walk + 1, extent.references + 1 + next.references);
    }
    return extent;
  }

  // Named by the first object below kiln's conversion, where the chain starts.
  error too_deep(const config_object& last, const std::string& more) const {
    const std::string start = describe(chain_.empty() ? last : chain_.front().first);
    return refused(start, "its references nest more than " + std::to_string(max_depth) +
                              " deep, counting GroupTransforms (" + chain_text(0, last) + more + ")");
  }

  // "colour space 'A' [to_scene_reference: ColorSpaceTransform dst] -> ... -> colour space 'A'",
  // the middle of a long chain left out.
  std::string chain_text(size_t from, const config_object& last) const {
    std::string text;
    for (size_t i = from; i < chain_.size(); ++i) {
      if (i - from == 3 && chain_.size() - i > 2) {
        text += "... (" + std::to_string(chain_.size() - i - 2) + " more) -> ";
        i = chain_.size() - 2;
      }
      text += describe(chain_[i].first) + " [" + chain_[i].second + "] -> ";
    }
    return text + describe(last);
  }

  error refused(const std::string& location, const std::string& why) const {
    return input_error(config_.path, location,
                       why +
                           "; OpenColorIO follows references recursively, unbounded, and would overflow "
                           "its stack or never finish (config from " +
                           config_.named_by + ")");
  }

  reference_finder find_;
  const colour_config_source& config_;
  std::map<std::string, walk_extent> finished_;
  std::vector<std::pair<config_object, std::string>> chain_;  // each object and the reference taken from it
  std::vector<config_object> reached_;                        // each finished object, once
};

}  // namespace

std::vector<held_transform> check_references(const OCIO::Config& cfg,
                                             const OCIO::ConstTransformRcPtr& conversion,
                                             const colour_config_source& config) {
  reference_walk walk(cfg, config);
  walk.check_conversion(conversion);
  std::vector<held_transform> out{{conversion, "kiln's conversion"}};
  for (held_transform& h : walk.held()) out.push_back(std::move(h));
  return out;
}

}  // namespace kiln::colour_module
