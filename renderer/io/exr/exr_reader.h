// Reads an OpenEXR image with its pixels in the file's own per-channel formats (half stays half,
// float stays float), so images can be joined without changing a bit. Hides OpenEXR.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "io/exr/exr_value.h"
#include "render/film.h"

namespace kiln {

class memory_budget;

// The whole header as read (attributes, channel formats, windows); opaque outside io/exr.
struct exr_header;

struct exr_image {
  pixel_rect data_window;     // the stored pixels, in frame coordinates
  pixel_rect display_window;  // the full frame
  // Part after part, each part's in its channel list's (alphabetical) order.
  std::vector<std::string> channel_names;
  std::vector<std::string> channel_formats;  // per channel: "half", "float", "uint", ...
  std::vector<size_t> channel_bytes;         // per channel, in the native format
  // Row-major over the data window, each pixel's channels in order, each in its own format.
  std::vector<unsigned char> pixels;
  std::shared_ptr<const exr_header> header;

  size_t pixel_bytes() const;
};

// Throws kiln::error (input) naming path when the file cannot be opened or read, or when its data
// window's pixels do not fit what is left of budget (when given), charged before they are made.
exr_image read_exr(const std::string& path, memory_budget* budget = nullptr);

// The header's string attribute name (e.g. "kiln/settings_hash"), empty when it has none.
std::string exr_string_attribute(const exr_image& image, const std::string& name);

// The header's float attribute name (e.g. "renderTimeSeconds"); empty when it has none.
std::optional<float> exr_float_attribute(const exr_image& image, const std::string& name);

// Sets the attribute name, as the type value holds, on every part of image's header (a copy:
// other images that share the header keep theirs), replacing one of that name of any type.
void set_exr_attribute(exr_image& image, const std::string& name, const exr_value& value);

}  // namespace kiln
