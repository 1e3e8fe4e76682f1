// Replays every input the fuzzers found (tests/data/fuzz_regressions/) through the loader. Each
// one once crashed or tripped a sanitizer; each must now be refused with one clear kiln::error
// naming the file. Under the sanitizer stage of the test command, any memory error fails here.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "io/gltf/gltf_loader.h"

namespace kiln {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> regression_inputs() {
  std::vector<std::string> files;
  for (const auto& entry :
       fs::directory_iterator(std::string(KILN_SOURCE_DIR) + "/tests/data/fuzz_regressions")) {
    std::string ext = entry.path().extension().string();
    if (ext == ".gltf" || ext == ".glb") files.push_back(entry.path().string());
  }
  std::sort(files.begin(), files.end());
  return files;
}

TEST(fuzz_regressions, every_found_input_is_refused_with_a_clear_error) {
  const std::vector<std::string> files = regression_inputs();
  ASSERT_FALSE(files.empty());
  for (const std::string& file : files) {
    SCOPED_TRACE(file);
    try {
      load_gltf(file);
      ADD_FAILURE() << "loaded without error";
    } catch (const error& e) {
      EXPECT_EQ(e.kind(), error_kind::input);
      EXPECT_EQ(e.file(), file);
      EXPECT_FALSE(e.reason().empty());
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
    }
  }
}

TEST(fuzz_regressions, position_reference_is_checked_before_other_attributes_use_it) {
  const std::string file = std::string(KILN_SOURCE_DIR) +
                           "/tests/data/fuzz_regressions/position_index_out_of_range_after_normal.gltf";
  try {
    load_gltf(file);
    FAIL() << "loaded without error";
  } catch (const error& e) {
    EXPECT_NE(e.location().find("/attributes/POSITION"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace kiln
