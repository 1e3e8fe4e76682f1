// KHR_draco_mesh_compression, with streams made by Draco's own encoder in the test (so no sample
// asset is needed): decoded positions, normals and triangles land in the scene within the
// quantisation, whatever index width the accessor declares; broken streams, missing attribute ids
// and counts that disagree are refused on one line naming the extension's JSON pointer.
#include <draco/compression/decode.h>
#include <draco/compression/encode.h>
#include <draco/mesh/triangle_soup_mesh_builder.h>

#include "io/gltf/draco_header.h"
#include "io/gltf/draco_stream.h"
#include "io/gltf/gltf_loader.h"
#include "io/gltf/gltf_test_util.h"

namespace kiln {
namespace {

using namespace kiln::gltf_test;

constexpr const char* ext_pointer = "/meshes/0/primitives/0/extensions/KHR_draco_mesh_compression";

// A 6x6 grid of quads in z = 0.25 x (a ramp), each vertex's normal (0, 0, 1).
struct grid_mesh {
  std::vector<std::array<float, 3>> corners;  // three per triangle
};

grid_mesh make_grid() {
  grid_mesh g;
  auto p = [](int i, int j) { return std::array<float, 3>{i / 6.0f, j / 6.0f, 0.25f * i / 6.0f}; };
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j)
      for (auto c : {p(i, j), p(i + 1, j), p(i + 1, j + 1), p(i, j), p(i + 1, j + 1), p(i, j + 1)})
        g.corners.push_back(c);
  return g;
}

// Encodes the grid: attribute id 0 is POSITION (14-bit quantisation), id 1 NORMAL.
std::vector<uint8_t> encode(const grid_mesh& g) {
  draco::TriangleSoupMeshBuilder builder;
  const int faces = int(g.corners.size() / 3);
  builder.Start(faces);
  const int pos = builder.AddAttribute(draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32);
  const int nrm = builder.AddAttribute(draco::GeometryAttribute::NORMAL, 3, draco::DT_FLOAT32);
  const std::array<float, 3> up = {0, 0, 1};
  for (int f = 0; f < faces; ++f) {
    builder.SetAttributeValuesForFace(pos, draco::FaceIndex(f), g.corners[3 * f].data(),
                                      g.corners[3 * f + 1].data(), g.corners[3 * f + 2].data());
    builder.SetAttributeValuesForFace(nrm, draco::FaceIndex(f), up.data(), up.data(), up.data());
  }
  std::unique_ptr<draco::Mesh> mesh = builder.Finalize();
  draco::Encoder encoder;
  encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, 14);
  encoder.SetAttributeQuantization(draco::GeometryAttribute::NORMAL, 10);
  draco::EncoderBuffer buffer;
  EXPECT_TRUE(encoder.EncodeMeshToBuffer(*mesh, &buffer).ok());
  return std::vector<uint8_t>(buffer.data(), buffer.data() + buffer.size());
}

uint32_t point_count(const std::vector<uint8_t>& stream) {
  draco::DecoderBuffer buffer;
  buffer.Init(reinterpret_cast<const char*>(stream.data()), stream.size());
  return draco::Decoder().DecodeMeshFromBuffer(&buffer).value()->num_points();
}

// A document whose one primitive is the Draco stream (accessors without bufferViews).
gltf_builder draco_document(const std::vector<uint8_t>& stream, uint32_t points, size_t indices,
                            int index_type = k_ushort) {
  gltf_builder b;
  const int view = b.add_view(stream.data(), stream.size());
  const int pos = b.add_accessor(-1, k_float, points, "VEC3");
  b.doc["accessors"][size_t(pos)]["min"] = {0.0, 0.0, 0.0};
  b.doc["accessors"][size_t(pos)]["max"] = {1.0, 1.0, 0.25};
  const int nrm = b.add_accessor(-1, k_float, points, "VEC3");
  const int idx = b.add_accessor(-1, index_type, indices, "SCALAR");
  const json ext = {{"bufferView", view}, {"attributes", {{"POSITION", 0}, {"NORMAL", 1}}}};
  const int mesh = b.add_mesh({{"attributes", {{"POSITION", pos}, {"NORMAL", nrm}}},
                               {"indices", idx},
                               {"extensions", {{"KHR_draco_mesh_compression", ext}}}});
  b.set_scene({b.add_node({{"mesh", mesh}})});
  b.doc["extensionsUsed"] = {"KHR_draco_mesh_compression"};
  b.doc["extensionsRequired"] = {"KHR_draco_mesh_compression"};
  return b;
}

TEST(draco, decoded_mesh_matches_the_encoded_one_for_any_index_width) {
  temp_folder dir;
  const grid_mesh g = make_grid();
  const std::vector<uint8_t> stream = encode(g);
  const uint32_t points = point_count(stream);
  for (const int index_type : {k_ubyte, k_ushort, k_uint}) {
    SCOPED_TRACE(index_type);
    const std::string path =
        draco_document(stream, points, g.corners.size(), index_type).write(dir.file("d.gltf"));
    const scene s = load_gltf(path);
    ASSERT_EQ(s.meshes.size(), 1u);
    const mesh& m = s.meshes[0];
    ASSERT_EQ(m.triangle_count(), g.corners.size() / 3);
    ASSERT_EQ(m.normals.size(), m.positions.size());
    // Every decoded corner is an encoded corner within the quantisation step (extent 1 / 2^14),
    // and every triangle keeps its winding (the ramp's normals face +z).
    for (size_t t = 0; t < m.triangle_count(); ++t) {
      const vec3 a = m.positions[m.indices[3 * t]], b = m.positions[m.indices[3 * t + 1]],
                 c = m.positions[m.indices[3 * t + 2]];
      EXPECT_GT(glm::cross(b - a, c - a).z, 0.0f) << "triangle " << t;
      for (const vec3& p : {a, b, c}) {
        float nearest = 1e9f;
        for (const auto& q : g.corners) nearest = std::min(nearest, glm::length(p - vec3(q[0], q[1], q[2])));
        EXPECT_LE(nearest, 1.0f / 16384);
      }
    }
    for (const vec3& n : m.normals) EXPECT_NEAR(n.z, 1.0f, 1e-3f);
  }
}

std::string load_error(const gltf_builder& b, const temp_folder& dir) {
  const std::string path = b.write(dir.file("bad.gltf"));
  return error_of([&] { load_gltf(path); });
}

TEST(draco, corrupt_stream_is_refused_naming_the_extension) {
  temp_folder dir;
  const grid_mesh g = make_grid();
  std::vector<uint8_t> stream = encode(g);
  const uint32_t points = point_count(stream);
  // Truncated: the decoder runs out of bytes.
  std::vector<uint8_t> cut(stream.begin(), stream.begin() + long(stream.size() / 2));
  std::string message = load_error(draco_document(cut, points, g.corners.size()), dir);
  EXPECT_NE(message.find(std::string(ext_pointer) + ": corrupt Draco stream"), std::string::npos) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos);
  // Not a Draco stream at all.
  message = load_error(draco_document(std::vector<uint8_t>(64, 0x5a), points, g.corners.size()), dir);
  EXPECT_NE(message.find(std::string(ext_pointer) + ": corrupt Draco stream"), std::string::npos) << message;
}

TEST(draco, missing_attribute_id_and_wrong_counts_are_refused) {
  temp_folder dir;
  const grid_mesh g = make_grid();
  const std::vector<uint8_t> stream = encode(g);
  const uint32_t points = point_count(stream);
  gltf_builder b = draco_document(stream, points, g.corners.size());
  b.doc["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"]["attributes"]["NORMAL"] = 7;
  std::string message = load_error(b, dir);
  EXPECT_NE(message.find("no attribute with id 7"), std::string::npos) << message;

  message = load_error(draco_document(stream, points + 1, g.corners.size()), dir);
  EXPECT_NE(message.find(std::string(ext_pointer) + "/attributes/NORMAL: the Draco stream decodes " +
                         std::to_string(points) + " points"),
            std::string::npos)
      << message;
  // More indices than the stream decodes: found after decoding. Fewer: the header already
  // declares more faces than the accessor holds, refused before decoding.
  message = load_error(draco_document(stream, points, g.corners.size() + 3), dir);
  EXPECT_NE(message.find(std::string(ext_pointer) + "/indices: the Draco stream decodes"), std::string::npos)
      << message;
  message = load_error(draco_document(stream, points, g.corners.size() - 3), dir);
  EXPECT_NE(message.find("the stream declares 72 faces"), std::string::npos) << message;

  gltf_builder no_view = draco_document(stream, points, g.corners.size());
  no_view.doc["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"]["bufferView"] = 9;
  message = load_error(no_view, dir);
  EXPECT_NE(message.find(std::string(ext_pointer) + "/bufferView"), std::string::npos) << message;
}

// The header's counts, read without libdraco, are what the encoder wrote: 72 faces, and no more
// vertices than the decoded points, for edgebreaker and sequential streams alike.
TEST(draco, header_counts_are_read_without_decoding) {
  const grid_mesh g = make_grid();
  const std::vector<uint8_t> edgebreaker = encode(g);
  const auto counts = gltf_internal::read_draco_declared_counts(edgebreaker.data(), edgebreaker.size());
  ASSERT_TRUE(counts);
  EXPECT_EQ(counts->faces, 72u);
  EXPECT_LE(counts->vertices, point_count(edgebreaker));
  EXPECT_GT(counts->vertices, 0u);
  // A sequential stream: "DRACO", 2.2, mesh, method 0, no flags, then the varints 72 and 49.
  const std::vector<uint8_t> sequential = {'D', 'R', 'A', 'C', 'O', 2, 2, 1, 0, 0, 0, 72, 49};
  const auto seq = gltf_internal::read_draco_declared_counts(sequential.data(), sequential.size());
  ASSERT_TRUE(seq);
  EXPECT_EQ(seq->faces, 72u);
  EXPECT_EQ(seq->vertices, 49u);
  EXPECT_FALSE(gltf_internal::read_draco_declared_counts(sequential.data(), 9));  // too short
}

// A header with the metadata flag (fuzz_draco_stream: behind it, 4.4 GB was asked for) is refused.
TEST(draco, a_stream_with_metadata_is_refused) {
  std::vector<uint8_t> stream = {'D', 'R', 'A', 'C', 'O', 1, 0x30, 1, 1, 0x00, 0xaa, 0, 0, 0, 0, 0x1a};
  stream.resize(100, 0x42);
  std::string problem;
  EXPECT_FALSE(gltf_internal::decode_draco_stream(stream.data(), stream.size(), {{0, 5126, 3}}, {}, problem));
  EXPECT_EQ(problem, "the stream carries Draco metadata, which kiln does not read");
}

// fuzz_draco_stream's out-of-memory input: an edgebreaker header of version 1.49 declaring
// 1,212,696,648 faces made libdraco reserve 4.85 GB. It is refused before the decoder runs.
TEST(draco, a_header_declaring_more_than_the_accessors_is_refused_unread) {
  std::vector<uint8_t> stream = {'D', 'R', 'A', 'C', 'O', 1, 0x31, 1, 1, 0, 0, 0, 0x08, 0x0c, 0x01, 0x0b};
  stream.resize(128, 0x48);
  std::string problem;
  const auto g =
      gltf_internal::decode_draco_stream(stream.data(), stream.size(), {{0, 5126, 3}}, {1000, 1000}, problem);
  EXPECT_FALSE(g);
  EXPECT_NE(problem.find("declares 1212696648 faces"), std::string::npos) << problem;
  // Through the loader: accessors for 10 triangles refuse the grid's 72 before decoding it.
  temp_folder dir;
  const std::vector<uint8_t> grid = encode(make_grid());
  const std::string message =
      error_of([&] { load_gltf(draco_document(grid, point_count(grid), 30).write(dir.file("few.gltf"))); });
  EXPECT_NE(message.find(std::string(ext_pointer) + ": corrupt Draco stream: the stream declares 72 faces"),
            std::string::npos)
      << message;
}

}  // namespace
}  // namespace kiln
