// The resume check of an EXR kiln wrote (flat or deep): the file is read to its end, band by band in
// bounded memory, and compared with what its header records (kiln/checksum) and what the job expects
// (its hashes), so a damaged or foreign output is never kept as done. Hides OpenEXR.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "render/film.h"

namespace kiln {

class memory_budget;

// A header attribute and the value the job expects it to hold, e.g. {"kiln/settings_hash", "9f…"}.
using expected_attributes = std::vector<std::pair<std::string, std::string>>;

struct exr_check {
  std::string problem;     // empty when the file is intact and current; else why not, a few words
  pixel_rect data_window;  // of a file whose header reads
  pixel_rect display_window;
};

// Checks the flat EXR at path: an OpenEXR file of flat parts whose string attributes equal expected,
// whose every pixel of every part reads, and whose layout and pixels give the kiln/checksum it
// records. Never throws for a bad file; budget (when given) is charged for the rows read at a time.
exr_check check_flat_exr(const std::string& path, const expected_attributes& expected, memory_budget* budget);

// The same for a deep scanline EXR (kiln's --deep file); each band's samples are charged to budget.
exr_check check_deep_exr(const std::string& path, const expected_attributes& expected, memory_budget* budget);

}  // namespace kiln
