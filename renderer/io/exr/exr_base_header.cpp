#include "io/exr/exr_base_header.h"

#include <OpenEXR/ImfDoubleAttribute.h>
#include <OpenEXR/ImfFloatAttribute.h>
#include <OpenEXR/ImfFloatVectorAttribute.h>
#include <OpenEXR/ImfIntAttribute.h>
#include <OpenEXR/ImfStandardAttributes.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <OpenEXR/ImfVecAttribute.h>

#include <array>
#include <ctime>
#include <string>

#include "io/exr/exr_header_copy.h"
#include "io/exr/exr_shot_time.h"

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

// framesPerSecond and timeCode, OpenEXR's standard names for a frame's place in its shot.
void add_shot_frame(Imf::Header& header, const exr_shot_frame& shot) {
  const frame_rate_fraction rate = frame_rate_of(shot.fps);
  Imf::addFramesPerSecond(header, Imf::Rational(rate.numerator, rate.denominator));
  if (const std::optional<smpte_time_code> t = smpte_time_code_of(shot.frames_since_start, shot.fps)) {
    Imf::TimeCode code(t->hours, t->minutes, t->seconds, t->frame);  // drop-frame off
    code.setFieldPhase(t->field_phase);
    Imf::addTimeCode(header, code);
  }
}

}  // namespace

void insert_exr_attribute(Imf::Header& header, const std::string& name, const exr_value& value) {
  // OpenEXR refuses to change an attribute's type: a foreign file may hold name as another one.
  if (header.find(name) != header.end()) header = header_without(header, name.c_str());
  const char* key = name.c_str();
  std::visit(
      [&](const auto& v) {
        using T = std::decay_t<decltype(v)>;
        if constexpr (std::is_same_v<T, std::string>) header.insert(key, Imf::StringAttribute(v));
        if constexpr (std::is_same_v<T, int>) header.insert(key, Imf::IntAttribute(v));
        if constexpr (std::is_same_v<T, float>) header.insert(key, Imf::FloatAttribute(v));
        if constexpr (std::is_same_v<T, double>) header.insert(key, Imf::DoubleAttribute(v));
        if constexpr (std::is_same_v<T, vec2>) header.insert(key, Imf::V2fAttribute(Imath::V2f(v.x, v.y)));
        if constexpr (std::is_same_v<T, vec3>)
          header.insert(key, Imf::V3fAttribute(Imath::V3f(v.x, v.y, v.z)));
        if constexpr (std::is_same_v<T, std::vector<float>>) header.insert(key, Imf::FloatVectorAttribute(v));
      },
      value);
}

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
  for (const auto& [key, value] : metadata.attributes) insert_exr_attribute(header, key, value);
  if (metadata.shot) add_shot_frame(header, *metadata.shot);
  return header;
}

}  // namespace kiln
