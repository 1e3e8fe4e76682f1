#include "io/exr/deep_writer.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfDeepFrameBuffer.h>
#include <OpenEXR/ImfDeepImageStateAttribute.h>
#include <OpenEXR/ImfDeepScanLineOutputFile.h>
#include <OpenEXR/ImfFloatAttribute.h>
#include <OpenEXR/ImfPartType.h>
#include <OpenEXR/ImfStringAttribute.h>

#include <algorithm>
#include <cstddef>
#include <cstring>
#include <vector>

#include "core/error.h"
#include "io/exr/exr_atomic_file.h"
#include "io/exr/exr_base_header.h"
#include "io/exr/exr_checksum.h"
#include "io/exr/exr_message.h"

namespace kiln {

const char* const deep_channel_names[10] = {
    "R", "G", "B", "A", "Z", "ZBack", "id.object", "id.material", "id.instance", "id.crypto_object"};

namespace {

// Where each channel's float sits in a deep_sample, in deep_channel_names' order.
const size_t channel_offsets[10] = {offsetof(deep_sample, rgba) + 0 * sizeof(float),
                                    offsetof(deep_sample, rgba) + 1 * sizeof(float),
                                    offsetof(deep_sample, rgba) + 2 * sizeof(float),
                                    offsetof(deep_sample, rgba) + 3 * sizeof(float),
                                    offsetof(deep_sample, z),
                                    offsetof(deep_sample, z_back),
                                    offsetof(deep_sample, object),
                                    offsetof(deep_sample, material),
                                    offsetof(deep_sample, instance),
                                    offsetof(deep_sample, crypto_object)};
constexpr int channel_count = 10;

// Rows given to OpenEXR at a time (each row is its own chunk with ZIPS).
constexpr int rows_per_write = 16;

Imf::Header deep_header(const deep_image& deep, const exr_metadata& metadata) {
  Imf::Header header = exr_base_header({deep.full_width, deep.full_height}, deep.region, metadata);
  header.setType(Imf::DEEPSCANLINE);
  // Deep scanline files take only single-line codecs (none, RLE, ZIPS): ZIPS is the smallest.
  header.compression() = Imf::ZIPS_COMPRESSION;
  for (const char* name : deep_channel_names) header.channels().insert(name, Imf::Channel(Imf::FLOAT));
  // Sorted always (merge_deep_samples); non-overlapping only where every pixel is.
  header.insert("deepImageState",
                Imf::DeepImageStateAttribute(deep.tidy() ? Imf::DIS_TIDY : Imf::DIS_SORTED));
  header.insert("kiln/deep_merge_tolerance", Imf::FloatAttribute(deep_merge_tolerance));
  return header;
}

// Rows [y0, y1) of deep as OpenEXR reads them: a sample count and, per channel, a pointer to the
// pixel's first sample, for each pixel. The pointers point into deep's tiles (never written).
struct deep_rows {
  std::vector<unsigned int> counts;
  std::vector<char*> first[channel_count];
};

deep_rows gather_rows(const deep_image& deep, int y0, int y1) {
  const int width = deep.region.width();
  deep_rows rows;
  rows.counts.resize(size_t(width) * size_t(y1 - y0));
  for (auto& f : rows.first) f.assign(rows.counts.size(), nullptr);
  for (int y = y0; y < y1; ++y)
    for (int x = deep.region.x0; x < deep.region.x1; ++x) {
      const deep_tile& t = deep.tile_at(x, y);
      const size_t in_tile = size_t(y - t.rect.y0) * size_t(t.rect.width()) + size_t(x - t.rect.x0);
      const size_t i = size_t(y - y0) * size_t(width) + size_t(x - deep.region.x0);
      rows.counts[i] = t.first[in_tile + 1] - t.first[in_tile];
      if (rows.counts[i] == 0) continue;
      char* sample = const_cast<char*>(reinterpret_cast<const char*>(&t.samples[t.first[in_tile]]));
      for (int c = 0; c < channel_count; ++c) rows.first[c][i] = sample + channel_offsets[c];
    }
  return rows;
}

// OpenEXR addresses pixel (x, y) of a slice at base + x·xStride + y·yStride: the base of rows
// starting at frame row y0, whose first pixel is frame column x0.
template <typename T>
char* slice_base(T* data, int x0, int y0, int width) {
  return reinterpret_cast<char*>(data) - (ptrdiff_t(x0) + ptrdiff_t(y0) * width) * ptrdiff_t(sizeof(T));
}

void write_deep_file(Imf::OStream& stream, const Imf::Header& header, const deep_image& deep,
                     const std::atomic<bool>* cancel) {
  Imf::DeepScanLineOutputFile out(stream, header, Imf::globalThreadCount());
  const int width = deep.region.width();
  for (int y0 = deep.region.y0; y0 < deep.region.y1; y0 += rows_per_write) {
    if (cancel && cancel->load()) throw error(error_kind::interrupted, "", "", "interrupted while writing");
    const int y1 = std::min(y0 + rows_per_write, deep.region.y1);
    deep_rows rows = gather_rows(deep, y0, y1);
    Imf::DeepFrameBuffer buffer;
    buffer.insertSampleCountSlice(Imf::Slice(Imf::UINT,
                                             slice_base(rows.counts.data(), deep.region.x0, y0, width),
                                             sizeof(unsigned int), sizeof(unsigned int) * size_t(width)));
    for (int c = 0; c < channel_count; ++c)
      buffer.insert(deep_channel_names[c],
                    Imf::DeepSlice(Imf::FLOAT, slice_base(rows.first[c].data(), deep.region.x0, y0, width),
                                   sizeof(char*), sizeof(char*) * size_t(width), sizeof(deep_sample)));
    out.setFrameBuffer(buffer);
    out.writePixels(y1 - y0);
  }
}

// The checksum deep_exr_checksum reads back from the file (io/exr/exr_checksum.h): the layout, then
// row by row the counts and the samples, each sample's channels in the header's (alphabetical) order.
std::string deep_checksum(const Imf::Header& header, const deep_image& deep) {
  std::vector<size_t> offsets;
  for (auto c = header.channels().begin(); c != header.channels().end(); ++c)
    for (int i = 0; i < channel_count; ++i)
      if (std::strcmp(c.name(), deep_channel_names[i]) == 0) offsets.push_back(channel_offsets[i]);
  content_crc crc;
  const std::string layout = exr_layout_text(header);
  crc.add(layout.data(), layout.size());
  std::vector<float> samples;
  for (int y = deep.region.y0; y < deep.region.y1; ++y) {
    const deep_rows row = gather_rows(deep, y, y + 1);
    samples.clear();
    for (size_t i = 0; i < row.counts.size(); ++i) {
      if (row.counts[i] == 0) continue;
      const char* first = row.first[0][i] - channel_offsets[0];  // the pixel's first deep_sample
      for (unsigned int s = 0; s < row.counts[i]; ++s)
        for (size_t offset : offsets) {
          float value;
          std::memcpy(&value, first + s * sizeof(deep_sample) + offset, sizeof value);
          samples.push_back(value);
        }
    }
    add_deep_row(crc, row.counts.data(), row.counts.size(), samples.data(), samples.size());
  }
  return crc.text();
}

}  // namespace

void write_deep_exr(const std::string& path, const deep_image& deep, const exr_metadata& metadata,
                    const std::atomic<bool>* cancel) {
  check_output_writable(path);
  if (deep.region.width() <= 0 || deep.region.height() <= 0 || deep.tiles.empty())
    throw io_error(path, "refusing to write an empty deep image");
  Imf::Header header;
  try {
    header = deep_header(deep, metadata);
    header.insert(exr_checksum_attribute, Imf::StringAttribute(deep_checksum(header, deep)));
  } catch (const std::exception& e) {  // e.g. a metadata key that is a standard attribute of another type
    throw io_error(path, "cannot write deep EXR: " + exr_message(e.what(), path));
  }
  write_exr_atomically(
      path, "deep EXR", [&](Imf::OStream& stream) { write_deep_file(stream, header, deep, cancel); }, cancel);
}

}  // namespace kiln
