#include "io/exr/exr_beauty.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputPart.h>
#include <OpenEXR/ImfMultiPartInputFile.h>
#include <OpenEXR/ImfPartType.h>

#include <exception>
#include <new>

#include "core/error.h"
#include "io/exr/exr_message.h"
#include "io/exr/exr_threads.h"

namespace kiln {

namespace {

constexpr const char* beauty_channels[4] = {"R", "G", "B", "A"};

bool has_beauty(const Imf::Header& header) {
  if (header.hasType() && Imf::isDeepData(header.type())) return false;
  for (const char* name : beauty_channels) {
    const Imf::Channel* channel = header.channels().findChannel(name);
    if (!channel || channel->xSampling != 1 || channel->ySampling != 1) return false;
  }
  return true;
}

}  // namespace

std::optional<rgba_image> read_exr_beauty(const std::string& path) {
  use_exr_threads();
  try {
    Imf::MultiPartInputFile file(path.c_str());
    for (int part = 0; part < file.parts(); ++part) {
      const Imf::Header& header = file.header(part);
      if (!has_beauty(header)) continue;
      const Imath::Box2i& window = header.dataWindow();
      rgba_image image;
      image.width = window.max.x - window.min.x + 1;
      image.height = window.max.y - window.min.y + 1;
      if (image.width <= 0 || image.height <= 0) throw input_error(path, "dataWindow", "no pixels to read");
      image.pixels.resize(size_t(image.width) * size_t(image.height) * 4);
      // OpenEXR converts half and uint samples to float as it reads them, exactly.
      Imf::FrameBuffer buffer;
      for (size_t c = 0; c < 4; ++c)
        buffer.insert(beauty_channels[c],
                      Imf::Slice::Make(Imf::FLOAT, image.pixels.data() + c, window, 4 * sizeof(float)));
      Imf::InputPart in(file, part);
      in.setFrameBuffer(buffer);
      in.readPixels(window.min.y, window.max.y);
      return image;
    }
    return std::nullopt;
  } catch (const error&) {
    throw;
  } catch (const std::bad_alloc&) {
    throw;                             // the caller's out-of-memory message names what it was doing
  } catch (const std::exception& e) {  // Iex::BaseExc for a damaged file
    throw input_error(path, "", "cannot read EXR: " + exr_message(e.what(), path));
  }
}

}  // namespace kiln
