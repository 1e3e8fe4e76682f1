// A deep scanline EXR read back with OpenEXR's own DeepScanLineInputFile, as a compositor reads it:
// every sample of every pixel, channel by channel, as float. For the deep-output and render-layer
// tests. Depends on OpenEXR only.
#pragma once

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfDeepFrameBuffer.h>
#include <OpenEXR/ImfDeepImageStateAttribute.h>
#include <OpenEXR/ImfDeepScanLineInputFile.h>
#include <OpenEXR/ImfHeader.h>

#include <algorithm>
#include <string>
#include <vector>

namespace kiln::testing {

// A deep file's every sample, channel by channel.
struct deep_file {
  int width = 0, height = 0;
  Imf::DeepImageState state = Imf::DIS_MESSY;
  bool has_state = false;
  std::vector<unsigned int> counts;
  std::vector<size_t> first;  // per pixel, into the channels
  std::vector<std::string> names;
  std::vector<std::vector<float>> channels;
  float at(size_t pixel, unsigned int k, const std::string& name) const {
    const auto c = std::find(names.begin(), names.end(), name) - names.begin();
    return channels[size_t(c)][first[pixel] + k];
  }
};

inline deep_file read_deep(const std::string& path) {
  deep_file out;
  Imf::DeepScanLineInputFile in(path.c_str());
  const Imath::Box2i dw = in.header().dataWindow();
  out.width = dw.max.x - dw.min.x + 1;
  out.height = dw.max.y - dw.min.y + 1;
  if (const auto* s = in.header().findTypedAttribute<Imf::DeepImageStateAttribute>("deepImageState")) {
    out.has_state = true;
    out.state = s->value();
  }
  const size_t n = size_t(out.width) * size_t(out.height);
  out.counts.resize(n);
  Imf::DeepFrameBuffer counts;
  counts.insertSampleCountSlice(Imf::Slice(Imf::UINT, reinterpret_cast<char*>(out.counts.data()),
                                           sizeof(unsigned int), sizeof(unsigned int) * size_t(out.width)));
  in.setFrameBuffer(counts);
  in.readPixelSampleCounts(dw.min.y, dw.max.y);
  out.first.resize(n + 1, 0);
  for (size_t i = 0; i < n; ++i) out.first[i + 1] = out.first[i] + out.counts[i];
  for (auto c = in.header().channels().begin(); c != in.header().channels().end(); ++c) {
    out.names.push_back(c.name());
    out.channels.emplace_back(out.first[n]);
  }
  Imf::DeepFrameBuffer buffer = counts;
  std::vector<std::vector<char*>> pointers(out.names.size(), std::vector<char*>(n));
  for (size_t c = 0; c < out.names.size(); ++c) {
    for (size_t i = 0; i < n; ++i)
      pointers[c][i] = reinterpret_cast<char*>(out.channels[c].data() + out.first[i]);
    buffer.insert(out.names[c],
                  Imf::DeepSlice(Imf::FLOAT, reinterpret_cast<char*>(pointers[c].data()), sizeof(char*),
                                 sizeof(char*) * size_t(out.width), sizeof(float)));
  }
  in.setFrameBuffer(buffer);
  in.readPixelSampleCounts(dw.min.y, dw.max.y);  // OpenEXR reads samples only after counts in this buffer
  in.readPixels(dw.min.y, dw.max.y);
  return out;
}

}  // namespace kiln::testing
