// Which files an asset may make kiln read: buffers and images resolve relative to the asset's
// folder; ".." escapes and absolute paths that leave it are refused unless allowed; percent-
// encoded URIs and names with spaces work. An asset in memory reads only the files given with it.
#include <gtest/gtest.h>

#include "io/gltf/gltf_loader.h"
#include "io/gltf/gltf_test_util.h"

namespace kiln {
namespace {

using namespace gltf_test;

// The single triangle with its buffer under the URI `uri`, written to dir/sub/scene.gltf; the
// buffer bytes go to dir/<bin_location> (relative to dir).
std::string write_with_buffer_at(const temp_folder& dir, const std::string& uri,
                                 const std::string& bin_location) {
  gltf_builder b = single_triangle();
  fs::create_directories(dir.file("sub"));
  const std::string path = dir.file("sub/scene.gltf");
  write_text(path, b.finished(uri).dump(2));
  write_bytes(dir.file(bin_location), b.bin);
  return path;
}

gltf_load_options allowing_outside() {
  gltf_load_options options;
  options.allow_files_outside_folder = true;
  return options;
}

TEST(GltfFileAccess, DotDotEscapeIsRefusedNamingTheReason) {
  temp_folder dir;
  const std::string path = write_with_buffer_at(dir, "../outside.bin", "outside.bin");
  const std::string message = error_of([&] { load_gltf(path); });
  EXPECT_EQ(message.rfind(path, 0), 0u) << message;
  EXPECT_NE(message.find("/buffers/0/uri"), std::string::npos) << message;
  EXPECT_NE(message.find("outside the asset's folder"), std::string::npos) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

TEST(GltfFileAccess, PercentEncodedDotDotEscapeIsRefused) {
  temp_folder dir;
  const std::string path = write_with_buffer_at(dir, "%2E%2E/outside.bin", "outside.bin");
  const std::string message = error_of([&] { load_gltf(path); });
  EXPECT_NE(message.find("outside the asset's folder"), std::string::npos) << message;
}

TEST(GltfFileAccess, DotDotEscapeLoadsWhenAllowed) {
  temp_folder dir;
  const std::string path = write_with_buffer_at(dir, "../outside.bin", "outside.bin");
  const scene s = load_gltf(path, allowing_outside());
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.meshes[0].positions[1], vec3(1, 0, 0));
}

TEST(GltfFileAccess, DotDotThatStaysInsideIsFine) {
  temp_folder dir;
  const std::string path = write_with_buffer_at(dir, "../sub/inside.bin", "sub/inside.bin");
  EXPECT_EQ(load_gltf(path).meshes.size(), 1u);
}

TEST(GltfFileAccess, AbsolutePathIsRefusedEvenWhenOutsideFilesAreAllowed) {
  temp_folder dir;
  const std::string path = write_with_buffer_at(dir, dir.file("absolute.bin"), "absolute.bin");
  for (const gltf_load_options& options : {gltf_load_options{}, allowing_outside()}) {
    const std::string message = error_of([&] { load_gltf(path, options); });
    EXPECT_NE(message.find("/buffers/0/uri"), std::string::npos) << message;
    EXPECT_NE(message.find("absolute path"), std::string::npos) << message;
  }
}

// A symlink inside the folder is judged by where it leads: the lexical path stays inside, the file
// it names does not.
TEST(GltfFileAccess, SymlinkLeadingOutOfTheFolderIsRefusedUnlessAllowed) {
  temp_folder dir;
  const std::string path = write_with_buffer_at(dir, "link.bin", "outside.bin");
  fs::create_symlink(dir.file("outside.bin"), dir.file("sub/link.bin"));
  const std::string message = error_of([&] { load_gltf(path); });
  EXPECT_NE(message.find("/buffers/0/uri"), std::string::npos) << message;
  EXPECT_NE(message.find("outside the asset's folder"), std::string::npos) << message;
  const scene s = load_gltf(path, allowing_outside());
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.meshes[0].positions[1], vec3(1, 0, 0));
}

TEST(GltfFileAccess, SymlinkToASystemFileIsRefused) {
  temp_folder dir;
  const std::string path = write_with_buffer_at(dir, "passwd", "unused.bin");
  fs::create_symlink("/etc/passwd", dir.file("sub/passwd"));
  const std::string message = error_of([&] { load_gltf(path); });
  EXPECT_NE(message.find("/buffers/0/uri"), std::string::npos) << message;
  EXPECT_NE(message.find("outside the asset's folder"), std::string::npos) << message;
}

TEST(GltfFileAccess, SymlinkThatStaysInsideIsFine) {
  temp_folder dir;
  fs::create_directories(dir.file("sub/data"));
  const std::string path = write_with_buffer_at(dir, "link.bin", "sub/data/real.bin");
  fs::create_symlink("data/real.bin", dir.file("sub/link.bin"));
  EXPECT_EQ(load_gltf(path).meshes.size(), 1u);
}

// The asset's own folder reached through a symlink (e.g. a farm's mounted project path) is
// still its folder.
TEST(GltfFileAccess, AssetFolderReachedThroughASymlinkLoads) {
  temp_folder dir;
  write_with_buffer_at(dir, "inside.bin", "sub/inside.bin");
  fs::create_directory_symlink(dir.file("sub"), dir.file("alias"));
  EXPECT_EQ(load_gltf(dir.file("alias/scene.gltf")).meshes.size(), 1u);
}

TEST(GltfFileAccess, ImageUriEscapeIsRefused) {
  temp_folder dir;
  gltf_builder b = single_triangle();
  b.doc["images"] = json::array({json{{"uri", "../../secret.png"}}});
  const std::string path = b.write(dir.file("scene.gltf"));
  const std::string message = error_of([&] { load_gltf(path); });
  EXPECT_NE(message.find("/images/0/uri"), std::string::npos) << message;
  EXPECT_NE(message.find("outside the asset's folder"), std::string::npos) << message;
}

TEST(GltfFileAccess, PercentEncodedUriWithSpacesLoads) {
  temp_folder dir;
  const std::string path = write_with_buffer_at(dir, "my%20data.bin", "sub/my data.bin");
  const scene s = load_gltf(path);
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.meshes[0].positions[2], vec3(0, 1, 0));
}

TEST(GltfFileAccess, PlainSpacesInUriLoad) {
  temp_folder dir;
  const std::string path = write_with_buffer_at(dir, "my data.bin", "sub/my data.bin");
  EXPECT_EQ(load_gltf(path).meshes.size(), 1u);
}

// The single triangle in memory, its buffer given under `given` while the JSON names `uri`.
gltf_load_options in_memory(const std::string& uri, const std::string& given, size_t bytes = 0) {
  const gltf_builder b = single_triangle();
  auto asset = std::make_shared<gltf_memory_asset>();
  const std::string text = b.finished(uri).dump();
  asset->document.assign(text.begin(), text.end());
  asset->files[given] = b.bin;
  if (bytes) asset->files[given].resize(bytes);
  gltf_load_options options;
  options.in_memory = asset;
  return options;
}

TEST(GltfFileAccess, AnAssetInMemoryReadsTheFilesGivenWithIt) {
  for (const auto& [uri, given] : {std::pair{"tri.bin", "tri.bin"}, {"my%20data.bin", "my%20data.bin"}}) {
    const scene s = load_gltf("<memory>", in_memory(uri, given));
    ASSERT_EQ(s.meshes.size(), 1u) << uri;
    EXPECT_EQ(s.meshes[0].positions[2], vec3(0, 1, 0));
    EXPECT_EQ(s.source, "<memory>");
  }
}

TEST(GltfFileAccess, AnAssetInMemoryReadsNoFile) {
  temp_folder dir;  // the URI names a file that exists, absolute or beside the working directory
  const std::string path = write_with_buffer_at(dir, "tri.bin", "sub/tri.bin");
  for (const std::string& uri : {dir.file("sub/tri.bin"), std::string("tri.bin")}) {
    const fs::path before = fs::current_path();
    fs::current_path(dir.file("sub"));
    const std::string message = error_of([&] { load_gltf(path, in_memory(uri, "other.bin")); });
    fs::current_path(before);
    EXPECT_NE(message.find("/buffers/0/uri"), std::string::npos) << message;
    EXPECT_NE(message.find("which was not given with the asset in memory"), std::string::npos) << message;
  }
}

TEST(GltfFileAccess, AnAssetInMemoryIsCheckedAsAFile) {
  const std::string message = error_of([] { load_gltf("<memory>", in_memory("tri.bin", "tri.bin", 5)); });
  EXPECT_NE(message.find("<memory>: /buffers/0/byteLength: byteLength is"), std::string::npos) << message;
  EXPECT_NE(message.find("the bytes given for 'tri.bin' are 5"), std::string::npos) << message;
  gltf_load_options small = in_memory("tri.bin", "tri.bin");
  small.limits.max_json_bytes = 10;
  EXPECT_NE(error_of([&] { load_gltf("<memory>", small); }).find("--max-json-bytes"), std::string::npos);
}

}  // namespace
}  // namespace kiln
