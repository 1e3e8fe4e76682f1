// The table of functions the colour module (kiln_colour.so, the only kiln code that links
// OpenColorIO) hands to kiln. Linking OpenColorIO would cost every process start 1.4-1.8 ms (a
// third of kiln --version's), so the module is opened only when a render names a working space or
// a config. Both sides are built by the same toolchain from this header, so C++ types pass through
// it and the functions throw kiln::error. Depends on the standard library only.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>

namespace kiln {

// Bumped whenever the table below changes; kiln refuses a module built with another value.
constexpr uint32_t colour_module_abi = 1;

// The largest config file kiln reads (the ACES studio config is 75 KB, ACES 1.2's 170 KB): a larger
// one is refused before a byte of it is read.
constexpr uint64_t max_colour_config_bytes = uint64_t(4) << 20;

// Where a config came from, for messages: the file and the option or variable that named it.
struct colour_config_source {
  std::string path;
  std::string named_by;  // "--ocio-config" or "$OCIO"
};

// A working space as a config defines it, relative to glTF's linear Rec.709.
struct working_space_info {
  std::string name;    // the config's own name for the space (an alias resolved)
  std::string source;  // the config's colour space taken as linear Rec.709 (see colour_loader.h)
  // rgb_working = M · rgb_rec709, row-major; the config's processor, checked to be a 3x3 matrix.
  std::array<double, 9> working_from_rec709{1, 0, 0, 0, 1, 0, 0, 0, 1};
};

// Applies a display/view to straight RGB in place: count pixels of three floats.
using display_transform = std::function<void(float* rgb, size_t count)>;

struct colour_functions {
  uint32_t abi = colour_module_abi;
  uint32_t table_bytes = sizeof(colour_functions);  // a second check that both sides agree on the layout

  // Reads and validates the config. Throws kiln::error (input) naming its file and option when it
  // is missing or broken.
  void (*check_config)(const colour_config_source& config) = nullptr;

  // The working space `space` (a colour space name or alias in the config). Throws kiln::error
  // (input) naming the config's file and option for a missing or broken config, and --working-space
  // for an unknown space, one the config cannot reach from linear Rec.709, or one that is not a
  // linear (3x3 matrix) transform of it.
  working_space_info (*working_space)(const colour_config_source& config, const std::string& space) = nullptr;

  // The transform from `space` (empty: the config's linear Rec.709) to a display/view of the config (empty
  // display or view: the config's default display, and that display's default view). Throws kiln::error
  // (input) naming
  // --display or --view for one the config does not have.
  display_transform (*display_view)(const colour_config_source& config, const std::string& space,
                                    const std::string& display, const std::string& view) = nullptr;
};

}  // namespace kiln

// The module's one exported symbol: its table, valid for the life of the process.
#define KILN_COLOUR_ENTRY "kiln_colour_table"
extern "C" const kiln::colour_functions* kiln_colour_table();
