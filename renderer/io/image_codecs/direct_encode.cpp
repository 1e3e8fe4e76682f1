#include "io/image_codecs/direct_encode.h"

// clang-format off
#include <cstdio>  // jpeglib.h needs FILE declared first
#include <jpeglib.h>
#include <jerror.h>  // after jpeglib.h, which it needs
// clang-format on
#include <png.h>
#include <zlib.h>

#include <csetjmp>
#include <memory>

namespace kiln {

namespace {

// ---- PNG ---------------------------------------------------------------------------------------

// What one encode fills; owned by encode_png's caller side, so nothing here needs a destructor when
// libpng leaves by longjmp.
struct png_sink {
  std::vector<unsigned char>* bytes = nullptr;
  bool out_of_memory = false;
  std::string message;
};

void write_png_bytes(png_structp png, png_bytep data, size_t n) {
  auto* sink = static_cast<png_sink*>(png_get_io_ptr(png));
  try {
    sink->bytes->insert(sink->bytes->end(), data, data + n);
  } catch (...) {  // no C++ exception may cross libpng's frames
    sink->out_of_memory = true;
  }
  if (sink->out_of_memory) png_error(png, "out of memory");
}

void flush_png(png_structp) {}

[[noreturn]] void png_failed(png_structp png, png_const_charp message) {
  auto* sink = static_cast<png_sink*>(png_get_error_ptr(png));
  sink->message = message ? message : "libpng error";
  png_longjmp(png, 1);
}

void png_warned(png_structp, png_const_charp) {}

// OpenImageIO 2.4's PNG file but for its compression: the same chunks (an sRGB chunk of absolute
// intent with its gAMA and cHRM, an oFFs of (0, 0) and a tEXt "oiio:ColorSpace" = "sRGB", which
// tools reading kiln's previews have always found there) and the same pixels, deflated at zlib
// level 1 after the Sub row filter instead of level 6 after libpng's adaptive choice among all
// five filters: a preview is for a quick look, and that search cost more than all the rest of
// writing one (docs/performance.md).
bool write_png(int width, int height, int channels, const unsigned char* codes, png_sink& sink) {
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &sink, png_failed, png_warned);
  if (!png) return false;
  png_infop info = png_create_info_struct(png);
  if (!info || setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, info ? &info : nullptr);
    return false;
  }
  png_set_write_fn(png, &sink, write_png_bytes, flush_png);
  png_set_compression_level(png, 1);
  png_set_compression_strategy(png, Z_DEFAULT_STRATEGY);
  png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_SUB);
  png_set_IHDR(png, info, png_uint_32(width), png_uint_32(height), 8,
               channels == 4 ? PNG_COLOR_TYPE_RGB_ALPHA : PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_set_oFFs(png, info, 0, 0, PNG_OFFSET_PIXEL);
  png_set_sRGB_gAMA_and_cHRM(png, info, PNG_sRGB_INTENT_ABSOLUTE);
  char key[] = "oiio:ColorSpace", value[] = "sRGB";
  png_text text{};
  text.compression = PNG_TEXT_COMPRESSION_NONE;
  text.key = key;
  text.text = value;
  png_set_text(png, info, &text, 1);
  png_write_info(png, info);
  const size_t row_bytes = size_t(width) * size_t(channels);
  for (int y = 0; y < height; ++y)
    png_write_row(png, const_cast<png_bytep>(codes + size_t(y) * row_bytes));  // libpng only reads it
  png_write_end(png, info);
  png_destroy_write_struct(&png, &info);
  return true;
}

// ---- JPEG --------------------------------------------------------------------------------------

// OpenImageIO's Exif block for an sRGB JPEG (APP1), field by field.
// clang-format off
constexpr unsigned char exif_srgb[] = {
    'E', 'x', 'i', 'f', 0, 0,                          // the APP1 block's name
    'I', 'I', 42, 0, 8, 0, 0, 0,                       // TIFF header: little-endian, IFD0 at offset 8
    1, 0,                                              // IFD0, one entry:
    0x69, 0x87, 4, 0, 1, 0, 0, 0, 26, 0, 0, 0,         //   the Exif IFD (LONG) at offset 26
    0, 0, 0, 0,                                        // no IFD1
    4, 0,                                              // the Exif IFD, four entries:
    0x00, 0x90, 7, 0, 4, 0, 0, 0, '0', '2', '3', '0',  //   ExifVersion "0230"
    0x01, 0x91, 7, 0, 4, 0, 0, 0, 1, 2, 3, 0,          //   ComponentsConfiguration Y Cb Cr
    0x00, 0xA0, 7, 0, 4, 0, 0, 0, '0', '1', '0', '0',  //   FlashpixVersion "0100"
    0x01, 0xA0, 3, 0, 1, 0, 0, 0, 1, 0, 0, 0,          //   ColorSpace (SHORT) 1: sRGB
    0, 0, 0, 0};                                       // no further IFD
// clang-format on

struct jpeg_failure {
  jpeg_error_mgr manager;  // first: libjpeg hands back a pointer to it
  std::jmp_buf jump;
};

[[noreturn]] void jpeg_failed(j_common_ptr c) {
  std::longjmp(reinterpret_cast<jpeg_failure*>(c->err)->jump, 1);
}

// Where libjpeg puts the file: a fixed chunk, appended to the caller's vector whenever it fills.
struct jpeg_sink {
  jpeg_destination_mgr manager;  // first: libjpeg hands back a pointer to it
  std::vector<unsigned char>* bytes = nullptr;
  unsigned char chunk[1 << 16];
};

// Appends n bytes of the chunk; false when the vector cannot grow (no C++ exception may cross
// libjpeg's frames).
bool append_chunk(jpeg_sink& sink, size_t n) {
  try {
    sink.bytes->insert(sink.bytes->end(), sink.chunk, sink.chunk + n);
  } catch (...) {
    return false;
  }
  sink.manager.next_output_byte = sink.chunk;
  sink.manager.free_in_buffer = sizeof sink.chunk;
  return true;
}

void start_jpeg_sink(j_compress_ptr cinfo) {
  auto* sink = reinterpret_cast<jpeg_sink*>(cinfo->dest);
  sink->manager.next_output_byte = sink->chunk;
  sink->manager.free_in_buffer = sizeof sink->chunk;
}

boolean empty_jpeg_sink(j_compress_ptr cinfo) {
  if (!append_chunk(*reinterpret_cast<jpeg_sink*>(cinfo->dest), sizeof(jpeg_sink::chunk)))
    ERREXIT1(cinfo, JERR_OUT_OF_MEMORY, 0);
  return TRUE;
}

void finish_jpeg_sink(j_compress_ptr cinfo) {
  auto* sink = reinterpret_cast<jpeg_sink*>(cinfo->dest);
  if (!append_chunk(*sink, sizeof sink->chunk - sink->manager.free_in_buffer))
    ERREXIT1(cinfo, JERR_OUT_OF_MEMORY, 0);
}

// One encode's state, on the heap (the chunk is 64 KiB) and owned by encode_jpeg: libjpeg may leave
// by longjmp.
struct jpeg_encode {
  jpeg_compress_struct cinfo{};
  jpeg_failure failure{};
  jpeg_sink sink{};
  char message[JMSG_LENGTH_MAX] = {};
};

// OpenImageIO 2.4's JPEG writer, call for call: libjpeg's defaults (JFIF 1.01, 4:2:0 chroma,
// Huffman tables not optimised), quality 95 with baseline tables, and its Exif block.
bool write_jpeg(int width, int height, const unsigned char* rgb, jpeg_encode& job) {
  jpeg_compress_struct& cinfo = job.cinfo;
  cinfo.err = jpeg_std_error(&job.failure.manager);
  job.failure.manager.error_exit = jpeg_failed;
  if (setjmp(job.failure.jump)) {
    (*cinfo.err->format_message)(reinterpret_cast<j_common_ptr>(&cinfo), job.message);
    jpeg_destroy_compress(&cinfo);
    return false;
  }
  jpeg_create_compress(&cinfo);
  job.sink.manager.init_destination = start_jpeg_sink;
  job.sink.manager.empty_output_buffer = empty_jpeg_sink;
  job.sink.manager.term_destination = finish_jpeg_sink;
  cinfo.dest = &job.sink.manager;
  cinfo.image_width = JDIMENSION(width);
  cinfo.image_height = JDIMENSION(height);
  cinfo.input_components = 3;
  cinfo.in_color_space = JCS_RGB;
  jpeg_set_defaults(&cinfo);
  jpeg_set_quality(&cinfo, 95, TRUE);
  jpeg_start_compress(&cinfo, TRUE);
  jpeg_write_marker(&cinfo, JPEG_APP0 + 1, exif_srgb, sizeof exif_srgb);
  const size_t row_bytes = size_t(width) * 3;
  while (cinfo.next_scanline < cinfo.image_height) {
    JSAMPROW row = const_cast<JSAMPROW>(rgb + size_t(cinfo.next_scanline) * row_bytes);  // only read
    jpeg_write_scanlines(&cinfo, &row, 1);
  }
  jpeg_finish_compress(&cinfo);
  jpeg_destroy_compress(&cinfo);
  return true;
}

}  // namespace

std::string encode_png(int width, int height, int channels, const unsigned char* codes,
                       std::vector<unsigned char>& png) {
  if (width <= 0 || height <= 0 || (channels != 3 && channels != 4))
    return "cannot encode a " + std::to_string(width) + "x" + std::to_string(height) + " image of " +
           std::to_string(channels) + " channels";
  png.clear();
  png_sink sink;
  sink.bytes = &png;
  if (write_png(width, height, channels, codes, sink)) return "";
  return sink.message.empty() ? "libpng could not start" : sink.message;
}

std::string encode_jpeg(int width, int height, const unsigned char* rgb, std::vector<unsigned char>& jpeg) {
  if (width <= 0 || height <= 0 || width > JPEG_MAX_DIMENSION || height > JPEG_MAX_DIMENSION)
    return "cannot encode a " + std::to_string(width) + "x" + std::to_string(height) + " JPEG";
  jpeg.clear();
  auto job = std::make_unique<jpeg_encode>();
  job->sink.bytes = &jpeg;
  return write_jpeg(width, height, rgb, *job) ? "" : job->message;
}

}  // namespace kiln
