#include "io/exr/exr_verify.h"

#include <OpenEXR/ImfRgbaFile.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "core/memory_budget.h"
#include "io/exr/deep_writer.h"
#include "io/exr/exr_reader.h"
#include "io/exr/exr_writer.h"
#include "io/exr/preview_record.h"
#include "io/exr/preview_writer.h"
#include "io/image_codecs/direct_encode.h"

namespace kiln {
namespace {

namespace fs = std::filesystem;

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("kiln_exr_verify_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir / name;
}

std::vector<char> bytes_of(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void write_bytes(const fs::path& path, const std::vector<char>& bytes) {
  std::ofstream(path, std::ios::binary | std::ios::trunc).write(bytes.data(), std::streamsize(bytes.size()));
}

const expected_attributes job = {{"kiln/settings_hash", "0123456789abcdef"}};

exr_metadata job_metadata() {
  exr_metadata m;
  m.attributes = {{"kiln/settings_hash", "0123456789abcdef"}};
  return m;
}

// 16x12 pixels of varied values: every channel, every pixel its own.
film varied_film() {
  film f(16, 12);
  uint32_t state = 12345;
  const auto next = [&state] {
    state = state * 1664525u + 1013904223u;
    return float(state >> 8) / float(1 << 24);
  };
  for (size_t i = 0; i < f.color.size(); ++i) {
    f.color[i] = vec4(next() * 4.0f, next(), next() * 0.5f, next());
    f.depth[i] = 1.0f + next() * 10.0f;
    f.vec3_layer(aov::normal)[i] = vec3(next(), next(), next());
  }
  return f;
}

struct storage_case {
  const char* name;
  exr_settings settings;
};

std::vector<storage_case> storage_cases() {
  std::vector<storage_case> cases;
  for (const char* codec : {"none", "zip", "piz", "rle", "b44", "dwaa", "pxr24"}) {
    exr_settings s;
    s.compression = codec;
    s.multipart = is_lossy_compression(codec);  // a lossy part may hold no data layer
    cases.push_back({codec, s});
  }
  exr_settings tiled;
  tiled.tile_size = 8;
  cases.push_back({"zip tiled", tiled});
  return cases;
}

TEST(exr_verify, an_intact_file_passes_under_every_codec_and_truncation_at_any_length_fails) {
  for (const storage_case& c : storage_cases()) {
    const fs::path path = scratch("intact.exr");
    write_exr(path.string(), varied_film(), c.settings, job_metadata());
    const exr_check good = check_flat_exr(path.string(), job, nullptr);
    EXPECT_EQ(good.problem, "") << c.name;
    EXPECT_EQ(good.data_window.width(), 16);
    EXPECT_NE(check_flat_exr(path.string(), {{"kiln/settings_hash", "other"}}, nullptr)
                  .problem.find("kiln/settings_hash 0123456789abcdef is not the job's other"),
              std::string::npos);
    const std::vector<char> bytes = bytes_of(path);
    for (size_t length = 0; length < bytes.size(); length += 1 + bytes.size() / 100) {
      write_bytes(path, std::vector<char>(bytes.begin(), bytes.begin() + std::ptrdiff_t(length)));
      EXPECT_NE(check_flat_exr(path.string(), job, nullptr).problem, "") << c.name << " cut to " << length;
    }
  }
}

// Every flipped byte either fails the check or leaves a file that reads back to the same pixels
// (a byte OpenEXR never uses, or an attribute the check does not compare).
TEST(exr_verify, a_flipped_byte_anywhere_fails_unless_the_pixels_read_back_the_same) {
  for (const storage_case& c : storage_cases()) {
    const fs::path path = scratch("flipped.exr");
    write_exr(path.string(), varied_film(), c.settings, job_metadata());
    const exr_image original = read_exr(path.string());
    const std::vector<char> bytes = bytes_of(path);
    int failed = 0, same = 0;
    for (size_t at = 0; at < bytes.size(); at += 1 + bytes.size() / 150) {
      std::vector<char> flipped = bytes;
      flipped[at] = char(flipped[at] ^ 0x21);
      write_bytes(path, flipped);
      if (!check_flat_exr(path.string(), job, nullptr).problem.empty()) {
        ++failed;
        continue;
      }
      const exr_image kept = read_exr(path.string());
      EXPECT_EQ(kept.pixels, original.pixels) << c.name << " byte " << at;
      EXPECT_EQ(kept.channel_names, original.channel_names) << c.name << " byte " << at;
      EXPECT_EQ(kept.display_window, original.display_window) << c.name << " byte " << at;
      ++same;
    }
    EXPECT_GT(failed, same) << c.name;  // most bytes of a small file are pixels
  }
}

// Replaces the first occurrence of `from` in the file with `to` (of the same size).
void patch(const fs::path& path, const std::string& from, const std::string& to) {
  std::vector<char> bytes = bytes_of(path);
  const auto at = std::search(bytes.begin(), bytes.end(), from.begin(), from.end());
  ASSERT_NE(at, bytes.end()) << from;
  std::copy(to.begin(), to.end(), at);
  write_bytes(path, bytes);
}

TEST(exr_verify, an_edited_window_channel_name_or_checksum_fails) {
  const fs::path path = scratch("edited.exr");
  const auto fresh = [&] { write_exr(path.string(), varied_film(), exr_settings{}, job_metadata()); };
  fresh();
  // displayWindow's max.x (15) becomes 16: a frame one pixel wider.
  const std::string window = std::string("displayWindow\0box2i\0", 20) + std::string("\x10\0\0\0", 4) +
                             std::string(8, '\0') + std::string("\x0f\0\0\0", 4);
  std::string wider = window;
  wider[wider.size() - 4] = '\x10';
  patch(path, window, wider);
  EXPECT_NE(check_flat_exr(path.string(), job, nullptr).problem.find("not the recorded kiln/checksum"),
            std::string::npos);
  fresh();
  patch(path, std::string("N.X\0", 4), std::string("N.W\0", 4));  // still in alphabetical order
  EXPECT_NE(check_flat_exr(path.string(), job, nullptr).problem.find("not the recorded kiln/checksum"),
            std::string::npos);
  fresh();
  patch(path, "crc32:", "crc32;");
  EXPECT_NE(check_flat_exr(path.string(), job, nullptr).problem.find("not the recorded kiln/checksum"),
            std::string::npos);
}

TEST(exr_verify, a_file_without_a_checksum_a_deep_file_or_none_at_all_fails) {
  const fs::path path = scratch("plain.exr");
  Imf::Header header(4, 2);
  header.insert("kiln/settings_hash", Imf::StringAttribute("0123456789abcdef"));
  std::vector<Imf::Rgba> pixels(8, Imf::Rgba(1.0f, 0.5f, 0.25f, 1.0f));
  {
    Imf::RgbaOutputFile out(path.c_str(), header, Imf::WRITE_RGBA);
    out.setFrameBuffer(pixels.data(), 1, 4);
    out.writePixels(2);
  }
  EXPECT_EQ(check_flat_exr(path.string(), job, nullptr).problem,
            "no kiln/checksum (written before kiln recorded one)");
  EXPECT_EQ(check_deep_exr(path.string(), job, nullptr).problem, "not a deep EXR");
  EXPECT_EQ(check_flat_exr(scratch("absent.exr").string(), job, nullptr).problem, "missing");
  write_bytes(path, {'n', 'o', 't'});
  EXPECT_EQ(check_flat_exr(path.string(), job, nullptr).problem, "not an OpenEXR file");
}

TEST(exr_verify, the_rows_read_at_a_time_are_charged_to_the_budget) {
  const fs::path path = scratch("budget.exr");
  write_exr(path.string(), varied_film(), exr_settings{}, job_metadata());
  memory_budget small(256);
  EXPECT_NE(check_flat_exr(path.string(), job, &small).problem.find("over the memory budget"),
            std::string::npos);
  memory_budget enough(size_t(1) << 20);
  EXPECT_EQ(check_flat_exr(path.string(), job, &enough).problem, "");
  EXPECT_EQ(enough.used(), 0u);  // given back
}

// 6x4 pixels, pixel i with i % 3 samples.
deep_image small_deep() {
  deep_image d;
  d.region = {0, 0, 6, 4};
  d.full_width = 6;
  d.full_height = 4;
  deep_tile t;
  t.rect = d.region;
  for (int i = 0; i < 24; ++i) {
    for (int s = 0; s < i % 3; ++s) {
      deep_sample sample;
      sample.rgba = vec4(0.1f * float(i), 0.2f, 0.3f, 0.5f);
      sample.z = 1.0f + float(s) + 0.01f * float(i);
      sample.z_back = sample.z;
      sample.object = float(i);
      t.samples.push_back(sample);
    }
    t.first.push_back(uint32_t(t.samples.size()));
  }
  d.tiles.push_back(t);
  return d;
}

// Where a single-part file's chunks start: after the magic number and version, the attributes
// (name, type, size, value) up to an empty name, and an offset table of `chunks` entries.
size_t chunks_start(const std::vector<char>& bytes, size_t chunks) {
  size_t at = 8;
  while (at < bytes.size() && bytes[at] != '\0') {
    at += std::strlen(&bytes[at]) + 1;  // name
    at += std::strlen(&bytes[at]) + 1;  // type
    int32_t size = 0;
    std::memcpy(&size, &bytes[at], sizeof size);
    at += sizeof size + size_t(size);
  }
  return at + 1 + 8 * chunks;
}

TEST(exr_verify, a_deep_file_is_read_to_its_end_and_every_cut_or_flipped_sample_fails) {
  const fs::path path = scratch("deep.exr");
  write_deep_exr(path.string(), small_deep(), job_metadata());
  const exr_check good = check_deep_exr(path.string(), job, nullptr);
  EXPECT_EQ(good.problem, "");
  EXPECT_EQ(good.data_window.width(), 6);
  EXPECT_EQ(check_flat_exr(path.string(), job, nullptr).problem, "a deep EXR, not a flat one");
  const std::vector<char> bytes = bytes_of(path);
  for (size_t length = 0; length < bytes.size(); ++length) {
    write_bytes(path, std::vector<char>(bytes.begin(), bytes.begin() + std::ptrdiff_t(length)));
    EXPECT_NE(check_deep_exr(path.string(), job, nullptr).problem, "") << "cut to " << length;
  }
  // The chunks, after the header and the offset table of its 4 rows, hold the counts and samples.
  int failed = 0, passed = 0;
  for (size_t at = chunks_start(bytes, 4); at < bytes.size(); ++at) {
    std::vector<char> flipped = bytes;
    flipped[at] = char(flipped[at] ^ 0x21);
    write_bytes(path, flipped);
    (check_deep_exr(path.string(), job, nullptr).problem.empty() ? passed : failed) += 1;
  }
  EXPECT_EQ(passed, 0);
  EXPECT_GT(failed, 0);
  memory_budget small(64);
  write_bytes(path, bytes);
  EXPECT_NE(check_deep_exr(path.string(), job, &small).problem.find("over the memory budget"),
            std::string::npos);
}

// Damaged deep files the fuzzer found that made OpenEXR allocate gigabytes from their headers:
// refused before OpenEXR reads them, or charged to the budget before it allocates.
TEST(exr_verify, headers_that_declare_more_than_the_file_holds_are_refused_before_openexr_reads_them) {
  const std::string folder = std::string(KILN_SOURCE_DIR) + "/tests/data/fuzz_regressions/";
  memory_budget budget(uint64_t(64) << 20);
  EXPECT_EQ(check_deep_exr(folder + "resume_deep_attribute_size_past_the_file.deep.exr", {}, &budget)
                .problem.rfind("header attribute ", 0),
            0u);
  EXPECT_EQ(check_deep_exr(folder + "resume_deep_channel_list_longer_than_declared.deep.exr", {}, &budget)
                .problem.rfind("its header does not parse", 0),
            0u);
  EXPECT_NE(check_deep_exr(folder + "resume_deep_window_wider_than_the_budget.deep.exr", {}, &budget)
                .problem.find("over the memory budget"),
            std::string::npos);
  EXPECT_EQ(budget.used(), 0u);
}

TEST(preview_record, every_changed_byte_of_a_preview_fails_its_record) {
  std::vector<unsigned char> codes(8 * 6 * 4);
  for (size_t i = 0; i < codes.size(); ++i) codes[i] = (unsigned char)(i * 37);
  for (const std::string format : {"png", "jpg"}) {
    const fs::path path = scratch("preview." + format);
    write_preview_image(path.string(), 8, 6, 4, codes);
    EXPECT_EQ(preview_file_problem(path.string(), 8, 6), "") << format;
    EXPECT_NE(preview_file_problem(path.string(), 8, 7), "") << format;
    const std::vector<char> bytes = bytes_of(path);
    const std::vector<unsigned char> data(bytes.begin(), bytes.end());
    const std::string name = format == "png" ? "png" : "jpeg";
    EXPECT_EQ(checksum_record_problem(data, name), "");
    for (size_t at = 0; at < data.size(); ++at) {
      std::vector<unsigned char> flipped = data;
      flipped[at] ^= 0x01;
      EXPECT_NE(checksum_record_problem(flipped, name), "") << format << " byte " << at;
    }
  }
  std::vector<unsigned char> plain;
  ASSERT_EQ(encode_png(8, 6, 4, codes.data(), plain), "");
  EXPECT_EQ(checksum_record_problem(plain, "png"),
            "no kiln/checksum record (written before kiln recorded one)");
  EXPECT_EQ(checksum_record_problem(with_checksum_record(plain, "png"), "png"), "");
}

}  // namespace
}  // namespace kiln
