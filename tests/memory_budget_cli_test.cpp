// The job's memory budget from outside (--max-memory): a file whose textures' mip pyramids pass it
// is refused with one line and exit 2 before anything is written; a file over the size limit is
// refused from stat() alone; an allocation that fails although the estimates fit (a ulimit
// below the budget) ends the job with a message and exit 1, never a signal.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <vector>

#include "support/run_kiln.h"

namespace {

namespace fs = std::filesystem;
using kiln::testing::run_kiln;
using kiln::testing::scratch_folder;

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// A quad whose base colour (sRGB) and metallic-roughness (linear) read one side × side PNG
// through a mip-mapped sampler: two pyramids, about 10.7 bytes a texel, over an image of 4.
std::string textured_quad(const std::string& folder, int side) {
  const std::string png = folder + "/texture.png";
  auto out = OIIO::ImageOutput::create(png);
  OIIO::ImageSpec spec(side, side, 3, OIIO::TypeDesc::UINT8);
  std::vector<uint8_t> texels(size_t(side) * side * 3, 128);
  EXPECT_TRUE(out && out->open(png, spec) && out->write_image(OIIO::TypeDesc::UINT8, texels.data()) &&
              out->close());
  const std::vector<float> data = {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0, 0, 1, 1, 1, 1, 0, 0, 0};
  std::ofstream(folder + "/quad.bin", std::ios::binary)
      .write(reinterpret_cast<const char*>(data.data()), std::streamsize(data.size() * sizeof(float)));
  const nlohmann::json doc = {
      {"asset", {{"version", "2.0"}}},
      {"scenes", {{{"nodes", {0}}}}},
      {"nodes", {{{"mesh", 0}, {"translation", {0, 0, -3}}}}},
      {"meshes",
       {{{"primitives",
          {{{"attributes", {{"POSITION", 0}, {"TEXCOORD_0", 1}}}, {"material", 0}, {"mode", 6}}}}}}},
      {"materials",
       {{{"pbrMetallicRoughness",
          {{"baseColorTexture", {{"index", 0}}}, {"metallicRoughnessTexture", {{"index", 0}}}}}}}},
      {"textures", {{{"source", 0}, {"sampler", 0}}}},
      {"samplers", {{{"minFilter", 9987}}}},
      {"images", {{{"uri", "texture.png"}}}},
      {"buffers", {{{"uri", "quad.bin"}, {"byteLength", 80}}}},
      {"bufferViews",
       {{{"buffer", 0}, {"byteLength", 48}}, {{"buffer", 0}, {"byteOffset", 48}, {"byteLength", 32}}}},
      {"accessors",
       {{{"bufferView", 0},
         {"componentType", 5126},
         {"count", 4},
         {"type", "VEC3"},
         {"min", {-1, -1, 0}},
         {"max", {1, 1, 0}}},
        {{"bufferView", 1}, {"componentType", 5126}, {"count", 4}, {"type", "VEC2"}}}},
  };
  std::ofstream(folder + "/quad.gltf") << doc.dump();
  return folder + "/quad.gltf";
}

TEST(MemoryBudget, PyramidsOverTheBudgetAreRefusedAndNothingIsWritten) {
  const std::string dir = scratch_folder("memory_pyramids");
  const std::string asset = textured_quad(dir, 1024);  // 4 MiB decoded, 10.7 MiB of pyramids
  const std::string out = dir + "/out.exr";
  // 12 MiB holds the image and its decoding (9 MiB), not the image and its two pyramids.
  const auto refused =
      run_kiln({"render", asset, "-o", out, "--width", "16", "--height", "16", "--max-memory", "12M"});
  EXPECT_EQ(refused.exit_code, 2) << refused.stderr_text;
  EXPECT_TRUE(contains(refused.stderr_text, "quad.gltf: the textures' mip pyramids need about 11 MiB more"))
      << refused.stderr_text;
  EXPECT_TRUE(contains(refused.stderr_text, "over the memory budget of 12 MiB (raise it with --max-memory)"))
      << refused.stderr_text;
  EXPECT_FALSE(fs::exists(out));
  // The same job with room for them renders.
  const auto rendered =
      run_kiln({"render", asset, "-o", out, "--width", "16", "--height", "16", "--max-memory", "64M"});
  EXPECT_EQ(rendered.exit_code, 0) << rendered.stderr_text;
  EXPECT_TRUE(fs::exists(out));
}

// Each part of a render's memory is named in a sentence that reads: the environment's tables too.
TEST(MemoryBudget, TheEnvironmentsTablesOverTheBudgetAreNamed) {
  const std::string dir = scratch_folder("memory_environment");
  const auto refused = run_kiln({"render", std::string(KILN_SOURCE_DIR) + "/scenes/cornell_box.gltf", "-o",
                                 dir + "/out.exr", "--max-memory", "1M"});
  EXPECT_EQ(refused.exit_code, 2) << refused.stderr_text;
  EXPECT_TRUE(contains(refused.stderr_text, "cornell_box.gltf: the environment's sampling tables need about"))
      << refused.stderr_text;
}

TEST(MemoryBudget, SizesAreBytesOrBinaryUnits) {
  const std::string dir = scratch_folder("memory_sizes");
  const std::string asset = textured_quad(dir, 64);
  for (const char* bad : {"12MB!", "1.5G", "0", "-4G", "G"}) {
    const auto r = run_kiln({"render", asset, "-o", dir + "/o.exr", "--max-memory", bad});
    EXPECT_EQ(r.exit_code, 2) << bad;
    EXPECT_TRUE(contains(r.stderr_text, "--max-memory")) << r.stderr_text;
  }
  // 1000 bytes: the refusal says so in the budget's own unit.
  const auto tiny = run_kiln({"render", asset, "-o", dir + "/o.exr", "--max-memory", "1000"});
  EXPECT_EQ(tiny.exit_code, 2);
  EXPECT_TRUE(contains(tiny.stderr_text, "over the memory budget of 1000 bytes")) << tiny.stderr_text;
}

TEST(MemoryBudget, FilesOverTheSizeLimitAreRefusedWithoutReadingThem) {
  const std::string dir = scratch_folder("memory_huge_file");
  // Sparse: 2.2 GB that take no disk, and would take seconds and gigabytes to read.
  const std::string asset = dir + "/huge.gltf";
  std::ofstream(asset).close();
  fs::resize_file(asset, 2200000000ull);
  const auto r = run_kiln({"render", asset, "-o", dir + "/o.exr"});
  EXPECT_EQ(r.exit_code, 2) << r.stderr_text;
  EXPECT_TRUE(contains(r.stderr_text, "huge.gltf: is 2200000000 bytes, over kiln's limit of 2147483647"))
      << r.stderr_text;

  // A buffer file the asset names, the same way.
  const std::string quad = textured_quad(dir, 4);
  fs::resize_file(dir + "/quad.bin", 2200000000ull);
  const auto buffer = run_kiln({"render", quad, "-o", dir + "/o.exr"});
  EXPECT_EQ(buffer.exit_code, 2) << buffer.stderr_text;
  EXPECT_TRUE(contains(buffer.stderr_text, "2200000000 bytes, over kiln's limit")) << buffer.stderr_text;
}

TEST(MemoryBudget, JsonWhoseParseWouldPassTheBudgetIsRefusedBeforeParsing) {
  const std::string dir = scratch_folder("memory_json");
  nlohmann::json doc = nlohmann::json::parse(std::ifstream(textured_quad(dir, 4)));
  // 2 MB of one-member objects: ~140 MB parsed, well inside --max-json-bytes.
  doc["asset"]["extras"]["padding"] = nlohmann::json::array();
  for (int i = 0; i < 260000; ++i) doc["asset"]["extras"]["padding"].push_back({{"k", 1}});
  std::ofstream(dir + "/padded.gltf") << doc.dump();
  const auto r = run_kiln({"render", dir + "/padded.gltf", "-o", dir + "/o.exr", "--max-memory", "64M"});
  EXPECT_EQ(r.exit_code, 2) << r.stderr_text;
  EXPECT_TRUE(contains(r.stderr_text, "padded.gltf: the JSON text and its parse need about"))
      << r.stderr_text;
  EXPECT_FALSE(fs::exists(dir + "/o.exr"));
}

// Runs kiln with its address space limited to `bytes`; the exit status as waitpid gives it.
int run_kiln_limited(const std::vector<std::string>& arguments, rlim_t bytes, const std::string& err_file) {
  const pid_t pid = fork();
  if (pid == 0) {
    const rlimit limit{bytes, bytes};
    setrlimit(RLIMIT_AS, &limit);
    freopen(err_file.c_str(), "w", stderr);
    freopen("/dev/null", "w", stdout);
    std::vector<char*> argv = {const_cast<char*>(KILN_BINARY)};
    for (const std::string& a : arguments) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execv(KILN_BINARY, argv.data());
    _exit(127);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  return status;
}

TEST(MemoryBudget, AnAllocationThatFailsWithinTheBudgetIsAnErrorNotACrash) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "AddressSanitizer reserves terabytes of address space: a binary built with it cannot start "
                  "under RLIMIT_AS (the release suite runs this test)";
#endif
  const std::string dir = scratch_folder("memory_rlimit");
  const std::string err = dir + "/stderr.txt";
  const std::string out = dir + "/out.exr";
  // A 64 GiB budget lets a 12000² film (9 GiB with the writer's copy) through; 1 GB of address
  // space does not.
  const int status = run_kiln_limited({"render", kiln::testing::copy_scene(dir), "-o", out, "-q", "--width",
                                       "12000", "--height", "12000", "--max-memory", "64G"},
                                      rlim_t(1) << 30, err);
  ASSERT_TRUE(WIFEXITED(status)) << "killed by signal " << (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
  EXPECT_EQ(WEXITSTATUS(status), 1);
  std::stringstream text;
  text << std::ifstream(err).rdbuf();
  EXPECT_TRUE(contains(text.str(), "cornell_box.gltf: out of memory while rendering")) << text.str();
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
