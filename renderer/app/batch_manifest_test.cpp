// Manifests and job planning for `kiln batch`, without rendering: JSON and CSV jobs become the
// render options they describe (defaults, then the job's fields, then its overrides), relative
// assets resolve against the manifest's folder and outputs against --out-dir, and malformed
// manifests are refused with the file, the JSON pointer or CSV line, and the problem.
#include "app/batch_manifest.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "app/batch_command.h"
#include "core/error.h"

namespace kiln {
namespace {

namespace fs = std::filesystem;

class manifest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir = fs::temp_directory_path() / ("kiln_manifest_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir / "assets");
  }
  void TearDown() override { fs::remove_all(dir); }

  std::string write(const std::string& name, const std::string& text) {
    std::ofstream(dir / name) << text;
    return (dir / name).string();
  }

  // The error message read_manifest throws for text in a file called name.
  std::string error_for(const std::string& name, const std::string& text) {
    const std::string path = write(name, text);
    try {
      read_manifest(path);
    } catch (const error& e) {
      EXPECT_EQ(e.kind(), error_kind::input);
      EXPECT_EQ(e.file(), path);
      return e.what();
    }
    ADD_FAILURE() << "no error for " << text;
    return "";
  }

  std::vector<batch_job> plan(const std::string& manifest_path) {
    batch_options options;
    options.manifest = manifest_path;
    options.out_dir = (dir / "out").string();
    return plan_batch(options);
  }

  fs::path dir;
};

TEST_F(manifest, json_jobs_apply_defaults_fields_and_overrides_in_that_order) {
  const std::string path = write("m.json", R"({
    "defaults": {"spp": 4, "max-depth": 6, "show-background": true},
    "jobs": [
      {"asset": "assets/a.gltf", "camera": "Cam", "resolution": "640x480", "spp": 16, "output": "a_cam.exr",
       "overrides": {"max-depth": 4, "aovs": "beauty,Z", "show-background": false}},
      {"asset": "b.glb", "camera": 2},
      {"asset": "/abs/c.gltf", "output": "sub/c.exr", "overrides": {"--fov": 30.5, "float": true}}
    ]})");
  const std::vector<batch_job> jobs = plan(path);
  ASSERT_EQ(jobs.size(), 3u);
  const render_options& a = jobs[0].entry->options;
  EXPECT_EQ(jobs[0].entry->error, "");
  EXPECT_EQ(a.input, (dir / "assets/a.gltf").string());
  EXPECT_EQ(a.output, (dir / "out/a_cam.exr").string());
  EXPECT_EQ(a.camera, "Cam");
  EXPECT_EQ(a.width, 640);
  EXPECT_EQ(a.height, 480);
  EXPECT_EQ(samples_per_pixel_of(a), 16);
  EXPECT_EQ(a.max_depth, 4);
  EXPECT_FALSE(a.show_background);
  EXPECT_EQ(aov_list_name(a.aovs), "beauty,Z");
  EXPECT_EQ(jobs[0].name, "a_cam");

  const render_options& b = jobs[1].entry->options;
  EXPECT_EQ(b.input, (dir / "b.glb").string());
  EXPECT_EQ(b.output, (dir / "out/b_2.exr").string());  // asset stem + _camera
  EXPECT_EQ(samples_per_pixel_of(b), 4);                // the manifest's default
  EXPECT_EQ(b.max_depth, 6);
  EXPECT_TRUE(b.show_background);
  EXPECT_FALSE(b.width.has_value());
  EXPECT_EQ(aov_list_name(b.aovs), "beauty,Z,N");

  const render_options& c = jobs[2].entry->options;
  EXPECT_EQ(c.input, "/abs/c.gltf");
  EXPECT_EQ(c.output, (dir / "out/sub/c.exr").string());
  EXPECT_EQ(jobs[2].name, "sub/c");
  EXPECT_DOUBLE_EQ(c.fov_degrees, 30.5);
  EXPECT_TRUE(c.full_float);
}

TEST_F(manifest, a_bare_json_array_is_a_list_of_jobs) {
  const std::vector<batch_job> jobs =
      plan(write("m.json", R"([{"asset": "x.gltf"}, {"asset": "y.gltf", "spp": 2}])"));
  ASSERT_EQ(jobs.size(), 2u);
  EXPECT_EQ(jobs[0].entry->options.output, (dir / "out/x.exr").string());
  EXPECT_EQ(samples_per_pixel_of(jobs[1].entry->options), 2);
}

TEST_F(manifest, csv_rows_apply_their_columns_and_quoted_overrides) {
  const std::string path = write("jobs.csv",
                                 "asset,camera,resolution,spp,output,overrides\n"
                                 "assets/a.gltf,Cam,320x240,8,a.exr,\"--max-depth 4 --aovs beauty,Z\"\n"
                                 "\n"
                                 "b.gltf,,,,,\"--background 0.5,0.25,0 --up '0, 0, 1'\"\n"
                                 "\"c, d.gltf\",1,,,,\n");
  const std::vector<batch_job> jobs = plan(path);
  ASSERT_EQ(jobs.size(), 3u);
  const render_options& a = jobs[0].entry->options;
  EXPECT_EQ(jobs[0].entry->error, "");
  EXPECT_EQ(a.input, (dir / "assets/a.gltf").string());
  EXPECT_EQ(a.output, (dir / "out/a.exr").string());
  EXPECT_EQ(a.camera, "Cam");
  EXPECT_EQ(a.width, 320);
  EXPECT_EQ(a.height, 240);
  EXPECT_EQ(samples_per_pixel_of(a), 8);
  EXPECT_EQ(a.max_depth, 4);
  EXPECT_EQ(aov_list_name(a.aovs), "beauty,Z");
  EXPECT_EQ(jobs[1].entry->error, "");
  EXPECT_EQ(samples_per_pixel_of(jobs[1].entry->options),
            default_samples_per_pixel);  // empty cells leave the defaults
  EXPECT_EQ(jobs[1].entry->options.background, std::optional<vec3>(vec3(0.5f, 0.25f, 0.0f)));
  EXPECT_EQ(jobs[1].entry->options.up, dvec3(0.0, 0.0, 1.0));  // a quoted argument inside the overrides
  EXPECT_EQ(jobs[2].entry->options.input, (dir / "c, d.gltf").string());
  EXPECT_EQ(jobs[2].entry->options.output, (dir / "out/c, d_1.exr").string());
}

TEST_F(manifest, bad_csv_rows_are_refused_with_file_and_line) {
  const std::string header = "asset,camera,resolution,spp,output,overrides\n";
  EXPECT_EQ(error_for("a.csv", header + "x.gltf,,,,,\ny.gltf,,,\n"),
            (dir / "a.csv").string() + ": line 3: expected 6 fields, got 4");
  EXPECT_EQ(error_for("b.csv", header + "x.gltf,,,four,,\n"),
            (dir / "b.csv").string() + ": line 2: spp: expected an integer, got 'four'");
  EXPECT_EQ(error_for("c.csv", header + "\nx.gltf,,640by480,,,\n"),
            (dir / "c.csv").string() +
                ": line 3: resolution: expected WIDTHxHEIGHT such as 640x480, got '640by480'");
  EXPECT_EQ(error_for("d.csv", "asset,colour\nx.gltf,red\n"),
            (dir / "d.csv").string() +
                ": line 1: unknown column 'colour' (expected asset, camera, resolution, spp, frames, fps, "
                "animation, turntable, variants, output, overrides)");
  EXPECT_EQ(error_for("e.csv", header + ",Cam,,,,\n"),
            (dir / "e.csv").string() + ": line 2: empty asset path");
  EXPECT_EQ(error_for("f.csv", header + "\"x.gltf,,,,,\n"),
            (dir / "f.csv").string() + ": line 2: unclosed quote");
}

TEST_F(manifest, bad_json_is_refused_with_file_and_json_pointer) {
  EXPECT_EQ(error_for("a.json", R"({"jobs": [{"asset": "x.gltf"}, {"asset": "y.gltf", "spp": "many"}]})"),
            (dir / "a.json").string() + ": /jobs/1/spp: expected an integer, got \"many\"");
  EXPECT_EQ(error_for("b.json", R"({"jobs": [{"asset": 3}]})"),
            (dir / "b.json").string() + ": /jobs/0/asset: expected a string, got number");
  EXPECT_EQ(error_for("c.json", R"({"jobs": [{"camera": "Cam"}]})"),
            (dir / "c.json").string() + ": /jobs/0: the job has no \"asset\"");
  EXPECT_EQ(error_for("d.json", R"({"jobs": [{"asset": "x.gltf", "sp": 3}]})"),
            (dir / "d.json").string() +
                ": /jobs/0/sp: unknown job field (expected asset, camera, resolution, spp, frames, fps, "
                "animation, turntable, variants, output, overrides)");
  EXPECT_EQ(error_for("e.json", R"({"jobs": [{"asset": "x.gltf", "overrides": {"aovs": ["beauty"]}}]})"),
            (dir / "e.json").string() +
                ": /jobs/0/overrides/aovs: expected a string, number or boolean, got array");
  EXPECT_EQ(error_for("f.json", R"({"jobs": {"asset": "x.gltf"}})"),
            (dir / "f.json").string() + ": /jobs: expected an array of jobs, got object");
  const std::string syntax = error_for("g.json", "{\"jobs\": [\n  {\"asset\": \"x.gltf\",}\n]}");
  EXPECT_EQ(syntax.rfind((dir / "g.json").string() + ": line 2, column ", 0), 0u) << syntax;
  EXPECT_NE(syntax.find("invalid JSON"), std::string::npos) << syntax;
}

TEST_F(manifest, a_bad_override_fails_only_its_job_with_the_parsers_message) {
  const std::vector<batch_job> jobs =
      plan(write("m.json", R"([{"asset": "x.gltf", "overrides": {"max-depth": 99}},
      {"asset": "y.gltf", "overrides": {"no-such-option": 1}}, {"asset": "z.gltf"}])"));
  ASSERT_EQ(jobs.size(), 3u);
  EXPECT_EQ(jobs[0].entry->error,
            "bad render options: --max-depth: expects an integer from 0 to 64, got '99'");
  EXPECT_NE(jobs[1].entry->error.find("--no-such-option"), std::string::npos) << jobs[1].entry->error;
  EXPECT_EQ(jobs[2].entry->error, "");
  EXPECT_EQ(jobs[0].entry->where, (dir / "m.json").string() + ": /0");
}

TEST_F(manifest, two_jobs_writing_one_output_are_refused_before_anything_renders) {
  const std::string path = write("m.json", R"([{"asset": "a/x.gltf"}, {"asset": "b/x.gltf"}])");
  try {
    plan(path);
    ADD_FAILURE() << "two jobs write out/x.exr";
  } catch (const error& e) {
    EXPECT_EQ(e.kind(), error_kind::input);
    EXPECT_EQ(std::string(e.what()), path + ": /1: writes " + (dir / "out/x.exr").string() + ", as does " +
                                         path + ": /0 (give one of them another output)");
  }
}

}  // namespace
}  // namespace kiln
