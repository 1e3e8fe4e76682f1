// The module's one exported symbol. Everything else is hidden (the module is built with hidden
// visibility), so its copies of inline code never stand in for kiln's.
#include "io/image_codecs/image_codecs.h"
#include "io/image_codecs/module/codecs_module.h"

namespace {

kiln::image_codecs make_table() {
  kiln::image_codecs table;
  table.decode = &kiln::codecs_module::decode;
  table.read_float_rgba = &kiln::codecs_module::read_float_rgba;
  return table;
}

}  // namespace

extern "C" __attribute__((visibility("default"))) const kiln::image_codecs* kiln_image_codecs_table() {
  static const kiln::image_codecs table = make_table();
  return &table;
}
