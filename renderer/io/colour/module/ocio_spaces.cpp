// Working spaces and display/views from an OpenColorIO config: the config is read once per path
// and process, a working space is the config's processor from linear Rec.709, sampled into a 3x3
// matrix and checked to be one.
#include "io/colour/module/ocio_spaces.h"

#include <OpenColorIO/OpenColorIO.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <optional>
#include <vector>

#include "core/closest_name.h"
#include "core/error.h"
#include "core/message_text.h"
#include "io/colour/module/ocio_inputs.h"
#include "io/colour/module/ocio_references.h"

namespace OCIO = OCIO_NAMESPACE;

namespace kiln::colour_module {
namespace {

// Names configs give glTF's linear Rec.709 (kiln's config, the ACES studio config, the ACES 1.x
// configs, Blender's); the first one the config knows (as a name or alias) is the source space.
const char* const rec709_names[] = {"Linear Rec.709 (sRGB)",     "lin_rec709",
                                    "Utility - Linear - sRGB",   "Linear Rec.709",
                                    "scene-linear Rec.709-sRGB", "Linear"};

// OCIO's messages may hold newlines; kiln's are one line.
std::string one_line(const std::string& text) { return kiln::shown(text); }

// The config at config.path, read once per process (configs are immutable once read).
OCIO::ConstConfigRcPtr read_config(const colour_config_source& config) {
  static std::mutex mutex;
  static std::map<std::string, OCIO::ConstConfigRcPtr> configs;
  const std::lock_guard<std::mutex> lock(mutex);
  if (auto found = configs.find(config.path); found != configs.end()) return found->second;
  try {
    OCIO::ConstConfigRcPtr read = read_checked_config(config);
    read->validate();
    configs.emplace(config.path, read);
    return read;
  } catch (const OCIO::Exception& e) {
    throw input_error(config.path, config.named_by, "not a valid OpenColorIO config: " + one_line(e.what()));
  }
}

// The config's processor for conversion, once the config objects it reaches are checked: reading
// a config does not follow its references, building a processor does, and a loop among them
// takes the process down with a stack overflow; it also reads the files they name, and a FIFO
// among them blocks it forever.
OCIO::ConstProcessorRcPtr checked_processor(const OCIO::ConstConfigRcPtr& cfg,
                                            const OCIO::ConstTransformRcPtr& conversion,
                                            const colour_config_source& config) {
  check_transform_inputs(*cfg, check_references(*cfg, conversion, config), config);
  return cfg->getProcessor(conversion);
}

// The processor from glTF's linear Rec.709 to space: from the config's own Rec.709 space when it
// has one, else through its aces_interchange role (ACES2065-1) and OCIO's builtin Bradford
// transforms (AP1 to Rec.709, ACEScg to ACES2065-1).
OCIO::ConstProcessorRcPtr from_rec709(const OCIO::ConstConfigRcPtr& cfg, const colour_config_source& config,
                                      const std::string& space, std::string& source) {
  for (const char* name : rec709_names)
    if (OCIO::ConstColorSpaceRcPtr cs = cfg->getColorSpace(name)) {
      source = cs->getName();
      auto to_space = OCIO::ColorSpaceTransform::Create();
      to_space->setSrc(source.c_str());
      to_space->setDst(space.c_str());
      return checked_processor(cfg, to_space, config);
    }
  if (!cfg->hasRole("aces_interchange")) return nullptr;
  auto rec709_to_ap1 = OCIO::BuiltinTransform::Create();
  rec709_to_ap1->setStyle("UTILITY - ACES-AP1_to_LINEAR-REC709_BFD");
  rec709_to_ap1->setDirection(OCIO::TRANSFORM_DIR_INVERSE);
  auto ap1_to_ap0 = OCIO::BuiltinTransform::Create();
  ap1_to_ap0->setStyle("ACEScg_to_ACES2065-1");
  auto to_space = OCIO::ColorSpaceTransform::Create();
  to_space->setSrc(cfg->getColorSpace("aces_interchange")->getName());
  to_space->setDst(space.c_str());
  auto group = OCIO::GroupTransform::Create();
  group->appendTransform(rec709_to_ap1);
  group->appendTransform(ap1_to_ap0);
  group->appendTransform(to_space);
  source = "linear Rec.709 through the aces_interchange role";
  return checked_processor(cfg, group, config);
}

// What to give instead of a name the config lacks: "; did you mean 'ACEScg'?" for a near miss, then
// the config's names of that kind, at most 16 (the ACES configs have dozens of colour spaces).
std::string other_names(const std::string& given, const std::vector<std::string>& names,
                        const std::string& kind) {
  std::string hint;
  if (const std::optional<std::string> near = closest_name(given, names))
    hint += "; did you mean " + kiln::quoted(*near) + "?";
  const size_t shown = std::min<size_t>(names.size(), 16);
  hint += " (its " + kind + ":";
  for (size_t i = 0; i < shown; ++i) hint += (i ? ", " : " ") + kiln::quoted(names[i]);
  if (names.size() > shown) hint += " and " + std::to_string(names.size() - shown) + " more";
  return hint + (names.empty() ? " none)" : ")");
}

std::array<double, 3> apply(const OCIO::ConstCPUProcessorRcPtr& cpu, std::array<double, 3> v) {
  float rgb[3] = {float(v[0]), float(v[1]), float(v[2])};
  cpu->applyRGB(rgb);
  return {rgb[0], rgb[1], rgb[2]};
}

}  // namespace

void check_config(const colour_config_source& config) { read_config(config); }

working_space_info working_space(const colour_config_source& config, const std::string& space) {
  const OCIO::ConstConfigRcPtr cfg = read_config(config);
  const OCIO::ConstColorSpaceRcPtr target = cfg->getColorSpace(space.c_str());
  if (!target) {
    std::vector<std::string> spaces;  // those a render can work in: data spaces are refused below
    for (int i = 0; i < cfg->getNumColorSpaces(); ++i)
      if (const OCIO::ConstColorSpaceRcPtr cs = cfg->getColorSpace(cfg->getColorSpaceNameByIndex(i)))
        if (!cs->isData()) spaces.push_back(cs->getName());
    throw input_error(config.path, "--working-space",
                      "the config has no colour space " + kiln::quoted(space) +
                          other_names(space, spaces, "colour spaces"));
  }
  if (target->isData())
    throw input_error(config.path, "--working-space",
                      kiln::quoted(space) + " is a data space, not a colour space");
  working_space_info info;
  info.name = target->getName();
  try {
    const OCIO::ConstProcessorRcPtr processor = from_rec709(cfg, config, info.name, info.source);
    if (!processor)
      throw input_error(config.path, "--working-space",
                        "the config has no linear Rec.709 colour space (such as \"Linear Rec.709 (sRGB)\" "
                        "or \"lin_rec709\") and no aces_interchange role to reach one");
    // Float32 CPU processing: the same arithmetic every conversion below is checked against.
    const OCIO::ConstCPUProcessorRcPtr cpu = processor->getOptimizedCPUProcessor(OCIO::OPTIMIZATION_NONE);
    for (int c = 0; c < 3; ++c) {
      std::array<double, 3> unit{0, 0, 0};
      unit[size_t(c)] = 1.0;
      const std::array<double, 3> column = apply(cpu, unit);
      for (int r = 0; r < 3; ++r) info.working_from_rec709[size_t(r * 3 + c)] = column[size_t(r)];
    }
    // Whatever transform brought them (a matrix, a CDL, an exponent), NaN or infinity in the
    // matrix would reach every converted colour, and the render would discard those samples.
    for (const double m : info.working_from_rec709)
      if (!std::isfinite(m))
        throw input_error(config.path, "--working-space",
                          "this config converts linear Rec.709 to " + kiln::quoted(info.name) +
                              " through non-finite numbers (" + std::to_string(m) + ")");
    // A matrix maps any colour as it maps the three primaries; a curve, an offset or a clamp
    // does not, and kiln converts factors and texels by the matrix alone.
    for (const std::array<double, 3> probe :
         {std::array<double, 3>{0, 0, 0}, {0.25, 2.0, 7.5}, {40.0, 0.03, 1.5}, {0.001, 0.002, 0.0005}}) {
      const std::array<double, 3> got = apply(cpu, probe);
      for (int r = 0; r < 3; ++r) {
        double expected = 0.0, size = 0.0;
        for (int c = 0; c < 3; ++c) {
          expected += info.working_from_rec709[size_t(r * 3 + c)] * probe[size_t(c)];
          size += std::abs(info.working_from_rec709[size_t(r * 3 + c)] * probe[size_t(c)]);
        }
        if (!(std::abs(got[size_t(r)] - expected) <= 1e-5 * size + 1e-9))  // NaN fails too
          throw input_error(config.path, "--working-space",
                            kiln::quoted(info.name) +
                                " is not a linear (3x3 matrix) transform of linear Rec.709 " +
                                "in this config; a working space must be scene-linear");
      }
    }
  } catch (const OCIO::Exception& e) {
    throw input_error(
        config.path, "--working-space",
        "cannot convert linear Rec.709 to " + kiln::quoted(info.name) + ": " + one_line(e.what()));
  }
  return info;
}

display_transform display_view(const colour_config_source& config, const std::string& space,
                               const std::string& display, const std::string& view) {
  const OCIO::ConstConfigRcPtr cfg = read_config(config);
  std::string from = space;
  for (const char* name : rec709_names)
    if (OCIO::ConstColorSpaceRcPtr cs = from.empty() ? cfg->getColorSpace(name) : nullptr)
      from = cs->getName();
  if (from.empty())
    throw input_error(
        config.path, "--preview",
        "the config has no linear Rec.709 colour space to show the render from; give --working-space");
  const std::string chosen_display = display.empty() ? cfg->getDefaultDisplay() : display;
  std::vector<std::string> displays, views;
  for (int i = 0; i < cfg->getNumDisplays(); ++i) displays.push_back(cfg->getDisplay(i));
  if (std::find(displays.begin(), displays.end(), chosen_display) == displays.end())
    throw input_error(config.path, "--display",
                      "the config has no display " + kiln::quoted(chosen_display) +
                          other_names(chosen_display, displays, "displays"));
  const std::string chosen_view = view.empty() ? cfg->getDefaultView(chosen_display.c_str()) : view;
  for (int i = 0; i < cfg->getNumViews(chosen_display.c_str()); ++i)
    views.push_back(cfg->getView(chosen_display.c_str(), i));
  if (std::find(views.begin(), views.end(), chosen_view) == views.end())
    throw input_error(config.path, "--view",
                      "the display " + kiln::quoted(chosen_display) + " has no view " +
                          kiln::quoted(chosen_view) + other_names(chosen_view, views, "views"));
  try {
    auto to_view = OCIO::DisplayViewTransform::Create();
    to_view->setSrc(from.c_str());
    to_view->setDisplay(chosen_display.c_str());
    to_view->setView(chosen_view.c_str());
    const OCIO::ConstCPUProcessorRcPtr cpu =
        checked_processor(cfg, to_view, config)->getDefaultCPUProcessor();
    return [cpu](float* rgb, size_t count) {
      OCIO::PackedImageDesc pixels(rgb, long(count), 1, 3);
      cpu->apply(pixels);
    };
  } catch (const OCIO::Exception& e) {
    throw input_error(config.path, "--view",
                      "cannot show " + kiln::quoted(from) + " on " + kiln::quoted(chosen_display) + "/" +
                          kiln::quoted(chosen_view) + ": " + one_line(e.what()));
  }
}

}  // namespace kiln::colour_module
