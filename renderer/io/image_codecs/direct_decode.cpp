#include "io/image_codecs/direct_decode.h"

// clang-format off
#include <cstdio>  // jpeglib.h needs FILE declared first
#include <jpeglib.h>
// clang-format on
#include <png.h>

#include <csetjmp>
#include <cstring>
#include <memory>
#include <vector>

#include "io/image_codecs/png_structure.h"

namespace kiln {

namespace {

bool starts_with(const uint8_t* data, size_t size, const char* magic, size_t n) {
  return size >= n && std::memcmp(data, magic, n) == 0;
}

// ---- PNG ---------------------------------------------------------------------------------------

struct png_source {
  const uint8_t* data;
  size_t size;
  size_t read;
};

void read_png_bytes(png_structp png, png_bytep out, size_t n) {
  auto* source = static_cast<png_source*>(png_get_io_ptr(png));
  if (source->size - source->read < n) png_error(png, "truncated");
  std::memcpy(out, source->data + source->read, n);
  source->read += n;
}

[[noreturn]] void png_failed(png_structp png, png_const_charp) { png_longjmp(png, 1); }
void png_warned(png_structp, png_const_charp) {}  // libpng's warnings (colour profiles) are harmless

// What a read fills; owned by the caller, so nothing here needs a destructor when libpng leaves by
// longjmp on an error.
struct png_job {
  png_source source{};
  uint64_t max_texels = 0;
  int width = 0, height = 0;
  std::vector<uint8_t> rgba;
  std::vector<png_bytep> rows;
};

// libpng transforms that give the module's codes: palette and tRNS expanded to RGB(A), grey
// replicated, alpha added opaque where the image has none; no gamma correction (the module applies
// none: glTF's colour spaces are the material slots').
bool read_png(png_job& job) {
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, nullptr, png_failed, png_warned);
  if (!png) return false;
  png_infop info = png_create_info_struct(png);
  if (!info || setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, info ? &info : nullptr, nullptr);
    return false;
  }
  png_set_read_fn(png, &job.source, read_png_bytes);
  png_read_info(png, info);
  const png_uint_32 width = png_get_image_width(png, info), height = png_get_image_height(png, info);
  const int depth = png_get_bit_depth(png, info), type = png_get_color_type(png, info);
  const bool fits =
      uint64_t(width) * height <= job.max_texels && width <= 0x7fffffffu && height <= 0x7fffffffu;
  if (depth > 8 || !fits) png_longjmp(png, 1);  // 16-bit images decode to float: the module's part
  const bool transparent = png_get_valid(png, info, PNG_INFO_tRNS) != 0;
  if (type == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(png);
  if (type == PNG_COLOR_TYPE_GRAY && depth < 8) png_set_expand_gray_1_2_4_to_8(png);
  if (transparent) png_set_tRNS_to_alpha(png);
  if (type == PNG_COLOR_TYPE_GRAY || type == PNG_COLOR_TYPE_GRAY_ALPHA) png_set_gray_to_rgb(png);
  if (!(type & PNG_COLOR_MASK_ALPHA) && !transparent) png_set_filler(png, 0xFF, PNG_FILLER_AFTER);
  png_set_interlace_handling(png);
  png_read_update_info(png, info);
  if (png_get_rowbytes(png, info) != size_t(width) * 4) png_longjmp(png, 1);
  job.width = int(width);
  job.height = int(height);
  job.rgba.resize(size_t(width) * height * 4);
  job.rows.resize(height);
  for (png_uint_32 y = 0; y < height; ++y) job.rows[y] = job.rgba.data() + size_t(y) * width * 4;
  png_read_image(png, job.rows.data());
  png_destroy_read_struct(&png, &info, nullptr);
  return true;
}

// ---- JPEG --------------------------------------------------------------------------------------

struct jpeg_failure {
  jpeg_error_mgr manager;  // first: libjpeg hands back a pointer to it
  std::jmp_buf jump;
  int warnings;
};

[[noreturn]] void jpeg_failed(j_common_ptr c) {
  std::longjmp(reinterpret_cast<jpeg_failure*>(c->err)->jump, 1);
}
void jpeg_message(j_common_ptr c, int level) {
  if (level < 0) ++reinterpret_cast<jpeg_failure*>(c->err)->warnings;  // corrupt data, as the module sees it
}

struct jpeg_job {
  const uint8_t* data;
  size_t size;
  uint64_t max_texels;
  int width = 0, height = 0;
  std::vector<uint8_t> rgba;
  jpeg_decompress_struct cinfo;
  jpeg_failure failure;
};

// libjpeg's default decompression (the module changes none of it), straight into RGBA with opaque
// alpha (libjpeg-turbo's JCS_EXT_RGBA: grey replicated, YCbCr converted as to RGB). CMYK and YCCK
// are the module's. Any warning hands the image to the module too.
bool read_jpeg(jpeg_job& job) {
  jpeg_decompress_struct& cinfo = job.cinfo;
  std::memset(&cinfo, 0, sizeof(cinfo));  // jpeg_destroy_decompress is then safe at any point
  cinfo.err = jpeg_std_error(&job.failure.manager);
  job.failure.manager.error_exit = jpeg_failed;
  job.failure.manager.emit_message = jpeg_message;
  job.failure.warnings = 0;
  if (setjmp(job.failure.jump)) {
    jpeg_destroy_decompress(&cinfo);
    return false;
  }
  jpeg_create_decompress(&cinfo);
  jpeg_mem_src(&cinfo, job.data, static_cast<unsigned long>(job.size));
  jpeg_read_header(&cinfo, TRUE);
  const bool supported = cinfo.jpeg_color_space == JCS_YCbCr || cinfo.jpeg_color_space == JCS_RGB ||
                         cinfo.jpeg_color_space == JCS_GRAYSCALE;
  if (!supported || uint64_t(cinfo.image_width) * cinfo.image_height > job.max_texels) {
    jpeg_destroy_decompress(&cinfo);
    return false;
  }
  cinfo.out_color_space = JCS_EXT_RGBA;
  jpeg_start_decompress(&cinfo);
  if (cinfo.output_components != 4) std::longjmp(job.failure.jump, 1);
  job.width = int(cinfo.output_width);
  job.height = int(cinfo.output_height);
  const size_t row_bytes = size_t(job.width) * 4;
  job.rgba.resize(row_bytes * size_t(job.height));
  while (cinfo.output_scanline < cinfo.output_height) {
    JSAMPROW row = job.rgba.data() + size_t(cinfo.output_scanline) * row_bytes;
    jpeg_read_scanlines(&cinfo, &row, 1);
  }
  jpeg_destroy_decompress(&cinfo);  // not finished: the module reads no further than the last row
  return job.failure.warnings == 0;
}

}  // namespace

std::optional<image> decode_directly(const uint8_t* data, size_t size, uint64_t max_texels) {
  if (starts_with(data, size, "\x89PNG\r\n\x1a\n", 8)) {
    if (!png_structure_problem(data, size).empty()) return std::nullopt;  // the module words it
    png_job job;
    job.source = {data, size, 0};
    job.max_texels = max_texels;
    if (!read_png(job)) return std::nullopt;
    image out;
    out.width = job.width;
    out.height = job.height;
    out.texels8 = std::move(job.rgba);
    return out;
  }
  if (starts_with(data, size, "\xFF\xD8\xFF", 3)) {
    auto job = std::make_unique<jpeg_job>();
    job->data = data;
    job->size = size;
    job->max_texels = max_texels;
    if (!read_jpeg(*job)) return std::nullopt;
    image out;
    out.width = job->width;
    out.height = job->height;
    out.texels8 = std::move(job->rgba);
    return out;
  }
  return std::nullopt;
}

}  // namespace kiln
