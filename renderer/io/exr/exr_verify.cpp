#include "io/exr/exr_verify.h"

#include <OpenEXR/ImfMultiPartInputFile.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <OpenEXR/ImfTestFile.h>

#include <exception>
#include <filesystem>

#include "core/error.h"
#include "io/exr/exr_checksum.h"
#include "io/exr/exr_header_scan.h"
#include "io/exr/exr_message.h"
#include "io/exr/exr_threads.h"

namespace kiln {

namespace {

pixel_rect rect_of(const Imath::Box2i& box) { return {box.min.x, box.min.y, box.max.x + 1, box.max.y + 1}; }

std::string string_attribute(const Imf::Header& header, const std::string& name) {
  const auto* value = header.findTypedAttribute<Imf::StringAttribute>(name);
  return value ? value->value() : std::string();
}

// The cheap checks first (the header against the job), then the whole file against its checksum.
exr_check check_exr(const std::string& path, const expected_attributes& expected, memory_budget* budget,
                    bool deep) {
  exr_check check;
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return {"missing", {}, {}};
  if (!std::filesystem::is_regular_file(path, ec)) return {"not a regular file", {}, {}};
  try {
    bool tiled = false, is_deep = false, multipart = false;
    if (!Imf::isOpenExrFile(path.c_str(), tiled, is_deep, multipart)) return {"not an OpenEXR file", {}, {}};
    if (is_deep != deep) return {deep ? "not a deep EXR" : "a deep EXR, not a flat one", {}, {}};
    const std::string sizes = exr_header_sizes_problem(path);
    if (!sizes.empty()) return {sizes, {}, {}};
    use_exr_threads();
    Imf::MultiPartInputFile file(path.c_str());
    const Imf::Header& header = file.header(0);
    check.data_window = rect_of(header.dataWindow());
    check.display_window = rect_of(header.displayWindow());
    for (const auto& [name, value] : expected) {
      const std::string recorded = string_attribute(header, name);
      if (recorded != value) {
        check.problem = recorded.empty() ? "no " + name + " in its header"
                                         : name + " " + recorded + " is not the job's " + value +
                                               " (written with other inputs or settings)";
        return check;
      }
    }
    const std::string recorded = string_attribute(header, exr_checksum_attribute);
    if (recorded.empty()) {
      check.problem = std::string("no ") + exr_checksum_attribute + " (written before kiln recorded one)";
      return check;
    }
    const std::string read =
        deep ? deep_exr_checksum(file, path, budget) : flat_exr_checksum(file, path, budget);
    if (read != recorded)
      check.problem = "its contents read back as " + read + ", not the recorded " + exr_checksum_attribute +
                      " " + recorded + " (damaged or edited)";
  } catch (const error& e) {
    check.problem = e.location().empty() ? e.reason() : e.location() + ": " + e.reason();
  } catch (const std::exception& e) {  // Iex::BaseExc for a damaged file, std::bad_alloc
    check.problem = "cannot be read to its end: " + exr_message(e.what(), path);
  }
  return check;
}

}  // namespace

exr_check check_flat_exr(const std::string& path, const expected_attributes& expected,
                         memory_budget* budget) {
  return check_exr(path, expected, budget, false);
}

exr_check check_deep_exr(const std::string& path, const expected_attributes& expected,
                         memory_budget* budget) {
  return check_exr(path, expected, budget, true);
}

}  // namespace kiln
