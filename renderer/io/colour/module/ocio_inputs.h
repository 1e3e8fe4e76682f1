// What a config hands OpenColorIO, checked before OpenColorIO reads it, as an asset's URIs are:
// the config file (a regular file within max_colour_config_bytes whose YAML lists at most
// max_config_entries entries), the files its FileTransforms name (regular files within
// max_lut_bytes: a FIFO would block OpenColorIO's read forever, /dev/zero never ends) and the
// values of its MatrixTransforms (finite). Internal to the colour module.
#pragma once

#include <OpenColorIO/OpenColorIO.h>

#include <cstdint>
#include <vector>

#include "io/colour/colour_module.h"
#include "io/colour/module/ocio_references.h"

namespace kiln::colour_module {

// OpenColorIO reads a config in time quadratic in its entries (ocio_config_text.h): 5000 of the
// costliest kind (named transforms) take it 0.7 s on a 2-core machine; the ACES studio configs
// list 480-620.
constexpr uint64_t max_config_entries = 5000;
// The distinct files one conversion reads, together. A 65^3 3D LUT is 7.4 MB as a .cube, about
// 11 MB as ACES 1.2's .spi3d, and loads in 0.3 s; OpenColorIO tries every format it knows on a
// file its own format fails to read, 4.6 s for 16 MiB of numbers none can use.
constexpr uint64_t max_lut_bytes = uint64_t(16) << 20;
// Each file a config names is looked for along every search path (configs give one to three).
constexpr int max_search_paths = 64;

// The config at config.path, read once it passes the checks above: OpenColorIO parses the bytes
// kiln scanned (with the config's folder as its working folder, as when it opens the file itself).
// Throws kiln::error (input) naming config.path and config.named_by: missing, not a regular file,
// too large, YAML the scan refuses, too many entries or search paths; OpenColorIO's own exceptions
// pass through.
OCIO_NAMESPACE::ConstConfigRcPtr read_checked_config(const colour_config_source& config);

// Checks the FileTransforms and MatrixTransforms among transforms (GroupTransforms followed), as
// check_references returns them. Throws kiln::error (input) naming config.path and where the
// transform is held: a file that is not a regular file or that names further files (a CTF
// <Reference>), files over max_lut_bytes together; a matrix or offset value not finite.
// A file OpenColorIO cannot find is left to OpenColorIO to report.
void check_transform_inputs(const OCIO_NAMESPACE::Config& cfg, const std::vector<held_transform>& transforms,
                            const colour_config_source& config);

}  // namespace kiln::colour_module
