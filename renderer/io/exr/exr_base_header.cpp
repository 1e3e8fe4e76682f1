#include "io/exr/exr_base_header.h"

#include <OpenEXR/ImfFloatAttribute.h>
#include <OpenEXR/ImfIntAttribute.h>
#include <OpenEXR/ImfStandardAttributes.h>
#include <OpenEXR/ImfStringAttribute.h>

#include <array>
#include <ctime>
#include <string>

namespace kiln {

namespace {

std::string capture_date() {
  const std::time_t now = std::time(nullptr);
  std::tm local{};
  ::localtime_r(&now, &local);
  char text[32];
  std::strftime(text, sizeof text, "%Y:%m:%d %H:%M:%S", &local);
  return text;
}

}  // namespace

Imf::Header exr_base_header(const exr_frame_size& frame, const pixel_rect& stored,
                            const exr_metadata& metadata) {
  const Imath::Box2i display(Imath::V2i(0, 0), Imath::V2i(frame.width - 1, frame.height - 1));
  const Imath::Box2i data(Imath::V2i(stored.x0, stored.y0), Imath::V2i(stored.x1 - 1, stored.y1 - 1));
  Imf::Header header(display, data);
  // The render's colour space: glTF's linear Rec.709 (D65) unless a working space was chosen.
  const std::array<float, 8>& xy = metadata.chromaticities;
  Imf::addChromaticities(header, Imf::Chromaticities(Imath::V2f(xy[0], xy[1]), Imath::V2f(xy[2], xy[3]),
                                                     Imath::V2f(xy[4], xy[5]), Imath::V2f(xy[6], xy[7])));
  // OpenEXR stores matrices row-major with row vectors (p' = p·M): the transpose of GLM's
  // column-vector convention, so M44f's row c is GLM's column c.
  Imath::M44f world_to_camera, world_to_ndc;
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) {
      world_to_camera[c][r] = float(metadata.world_to_camera[c][r]);
      world_to_ndc[c][r] = float(metadata.world_to_ndc[c][r]);
    }
  Imf::addWorldToCamera(header, world_to_camera);
  Imf::addWorldToNDC(header, world_to_ndc);
  header.insert("Software", Imf::StringAttribute(std::string("kiln ") + KILN_VERSION));
  header.insert("capDate", Imf::StringAttribute(capture_date()));
  for (const auto& [key, value] : metadata.attributes) header.insert(key, Imf::StringAttribute(value));
  for (const auto& [key, value] : metadata.float_attributes) header.insert(key, Imf::FloatAttribute(value));
  for (const auto& [key, value] : metadata.int_attributes) header.insert(key, Imf::IntAttribute(value));
  return header;
}

}  // namespace kiln
