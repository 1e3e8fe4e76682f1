// Which tinygltf kiln calls. Debian's libdraco.a carries draco's own build of tinygltf and
// stb_image, and GNU ld extracts that member for a symbol libtinygltf.so leaves undefined
// (stbi_image_free) whatever the link order; kiln then called draco's tinygltf, whose classes differ
// from Debian's headers, and crashed on every load. third_party_cmake links a copy of the archive
// without its glTF members; these checks fail if the bundled copy ever comes back.
#include <dlfcn.h>
#include <draco/compression/decode.h>
#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <cstdio>
#include <cstring>
#include <memory>
#include <string>

#include "io/gltf/gltf_loader.h"

namespace kiln {
namespace {

std::string library_of(const void* address) {
  Dl_info info{};
  if (dladdr(address, &info) == 0 || info.dli_fname == nullptr) return "";
  return info.dli_fname;
}

// The code address of a non-virtual member function (Itanium C++ ABI: its first word).
template <typename F>
const void* member_address(F f) {
  const void* address = nullptr;
  std::memcpy(&address, &f, sizeof address);
  return address;
}

std::string command_output(const std::string& command) {
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(command.c_str(), "r"), pclose);
  std::string out;
  char buffer[4096];
  while (pipe && fgets(buffer, sizeof buffer, pipe.get())) out += buffer;
  return out;
}

TEST(link_check, loader_calls_debians_tinygltf) {
  load_gltf(std::string(KILN_SOURCE_DIR) + "/scenes/cornell_box.gltf");  // crashed with draco's copy
  EXPECT_NE(library_of(reinterpret_cast<const void*>(&tinygltf::FileExists)).find("libtinygltf.so"),
            std::string::npos);
  EXPECT_NE(library_of(member_address(&tinygltf::TinyGLTF::LoadBinaryFromMemory)).find("libtinygltf.so"),
            std::string::npos);
  EXPECT_NE(library_of(member_address(&tinygltf::TinyGLTF::SetFsCallbacks)).find("libtinygltf.so"),
            std::string::npos);
}

TEST(link_check, draco_decoder_is_linked_into_the_binary) {
  const std::string self = library_of(reinterpret_cast<const void*>(&library_of));
  EXPECT_EQ(library_of(member_address(&draco::Decoder::DecodePointCloudFromBuffer)), self);
}

TEST(link_check, kiln_defines_no_tinygltf_or_stb_function) {
  const std::string binary = KILN_BINARY;
  const std::string defined = command_output("nm --defined-only -C '" + binary + "'");
  ASSERT_NE(defined.find(" T main"), std::string::npos) << "nm gave no symbols for " << binary;
  EXPECT_EQ(defined.find(" T tinygltf::"), std::string::npos);
  EXPECT_EQ(defined.find(" T stbi_"), std::string::npos);
  const std::string needed = command_output("readelf -d '" + binary + "'");
  EXPECT_NE(needed.find("[libtinygltf.so"), std::string::npos);
  EXPECT_EQ(needed.find("[libdraco.so"), std::string::npos);
}

}  // namespace
}  // namespace kiln
