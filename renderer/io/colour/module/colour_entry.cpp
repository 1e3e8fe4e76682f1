// The module's one exported symbol. Everything else is hidden (the module is built with hidden
// visibility), so its copies of inline code never stand in for kiln's.
#include "io/colour/colour_module.h"
#include "io/colour/module/ocio_spaces.h"

namespace {

kiln::colour_functions make_table() {
  kiln::colour_functions table;
  table.check_config = &kiln::colour_module::check_config;
  table.working_space = &kiln::colour_module::working_space;
  table.display_view = &kiln::colour_module::display_view;
  return table;
}

}  // namespace

extern "C" __attribute__((visibility("default"))) const kiln::colour_functions* kiln_colour_table() {
  static const kiln::colour_functions table = make_table();
  return &table;
}
