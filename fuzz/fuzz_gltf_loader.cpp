// libFuzzer target: arbitrary bytes as a .gltf/.glb file through kiln's loader to a Scene.
// The only acceptable outcomes are a Scene or a kiln::error; any other exception, crash,
// sanitizer report, hang or runaway allocation is a finding. The input is written to a file
// because the loader resolves buffers and images relative to the asset's folder; that folder
// also holds the demo scene's .bin and .png so inputs mutated from the demo scene reach deep.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "io/gltf/gltf_loader.h"

namespace {

namespace fs = std::filesystem;

std::string asset_path;

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  fs::path folder = fs::temp_directory_path() / ("kiln_fuzz_gltf_" + std::to_string(::getpid()));
  fs::create_directories(folder);
  const fs::path scenes = fs::path(KILN_SOURCE_DIR) / "scenes";
  for (const char* name : {"cornell_box.bin", "checker.png"})
    fs::copy_file(scenes / name, folder / name, fs::copy_options::overwrite_existing);
  asset_path = (folder / "asset.gltf").string();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  {
    std::ofstream out(asset_path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), std::streamsize(size));
  }
  try {
    kiln::scene s = kiln::load_gltf(asset_path);
    (void)s;
  } catch (const kiln::error&) {
    // A clear refusal is the expected outcome for most inputs.
  }
  return 0;
}
