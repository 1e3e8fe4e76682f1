// `kiln batch` end to end, through the real binary on copies of the demo scene at tiny sizes:
// manifests set what each job renders; a broken asset fails alone; --resume skips exactly the
// outputs that are complete and up to date; a --plan-only job rendered by hand with `kiln render`
// gives the batch's pixels and hashes. Signals and the folder lock: batch_signal_cli_test.cpp.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>

#include "support/batch_cli_files.h"
#include "support/gltf_builder.h"
#include "support/run_kiln.h"

namespace kiln {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;
using testing::command_result;
using testing::lines;
using testing::run_kiln;
using testing::scratch_folder;

using namespace batch_testing;

TEST(batch_cli, a_broken_asset_fails_alone_and_the_summary_says_why) {
  const fs::path dir = scratch_folder("batch_broken");
  copy_scene(dir / "assets/good");
  fs::create_directories(dir / "assets/broken");
  write_file(dir / "assets/broken/broken.gltf", "{\"asset\": {\"version\": \"2.0\"}, \"nodes\": [\n");
  const std::string missing = (dir / "assets/missing.gltf").string();
  const command_result result =
      run_kiln(batch_args({(dir / "assets/*/*.gltf").string(), missing, "--out-dir", (dir / "out").string(),
                           "--summary", (dir / "summary.json").string()}));
  EXPECT_EQ(result.exit_code, 1) << result.stderr_text;

  const json summary = read_json(dir / "summary.json");
  EXPECT_EQ(statuses(summary), (std::vector<std::string>{"failed", "rendered", "failed"}));
  const json& jobs = summary["jobs"];
  EXPECT_EQ(jobs[0]["asset"], (dir / "assets/broken/broken.gltf").string());
  EXPECT_NE(jobs[0]["error"].get<std::string>().find("broken.gltf"), std::string::npos) << jobs[0]["error"];
  EXPECT_TRUE(jobs[1]["error"].is_null());
  EXPECT_EQ(jobs[1]["output"], (dir / "out/cornell_box.exr").string());
  EXPECT_GT(jobs[1]["seconds"].get<double>(), 0.0);
  EXPECT_NE(jobs[2]["error"].get<std::string>().find("missing.gltf"), std::string::npos) << jobs[2]["error"];
  EXPECT_EQ(summary["totals"]["jobs"], 3);
  EXPECT_EQ(summary["totals"]["rendered"], 1);
  EXPECT_EQ(summary["totals"]["failed"], 2);
  EXPECT_EQ(summary["totals"]["skipped"], 0);
  EXPECT_EQ(summary["exit_code"], 1);
  EXPECT_EQ(files_in(dir / "out"), (std::vector<std::string>{"cornell_box.exr"}));
  const image good = read_image((dir / "out/cornell_box.exr").string());
  EXPECT_EQ(good.spec.width, 24);
  EXPECT_EQ(good.spec.height, 18);

  // One line per job, each followed by the batch line; nothing else.
  const std::vector<std::string> progress = lines(result.stderr_text);
  ASSERT_EQ(progress.size(), 6u) << result.stderr_text;
  EXPECT_EQ(progress[0].rfind("kiln batch: [1/3] broken failed ", 0), 0u) << progress[0];
  EXPECT_EQ(progress[2].rfind("kiln batch: [2/3] cornell_box rendered ", 0), 0u) << progress[2];
  EXPECT_EQ(progress[3].rfind("kiln batch: 2/3 done, 1 failed, ETA ", 0), 0u) << progress[3];
  EXPECT_EQ(progress[5].rfind("kiln batch: 3/3 done, 2 failed, ETA 0.0 s", 0), 0u) << progress[5];

  const command_result quiet = run_kiln(
      batch_args({(dir / "assets/*/*.gltf").string(), missing, "--out-dir", (dir / "out").string(), "-q"}));
  EXPECT_EQ(quiet.exit_code, 1);
  EXPECT_EQ(quiet.stderr_text, "");
}

// Each job runs in its own process: one that crashes for real (abort(), through the test-only
// KILN_TEST_ABORT_ASSET hook of kiln's main) is recorded as crashed with its signal, the later
// jobs still render, the summary is written, and --resume re-tries it once and finishes.
TEST(batch_cli, a_job_that_crashes_is_recorded_with_its_signal_and_the_batch_goes_on) {
  const fs::path dir = scratch_folder("batch_crash");
  const std::string a = copy_scene(dir / "assets", "a.gltf");
  const std::string crash = copy_scene(dir / "assets", "crash.gltf");
  const std::string c = copy_scene(dir / "assets", "c.gltf");
  const std::string out = (dir / "out").string(), summary = (dir / "summary.json").string();
  const std::vector<std::string> args =
      batch_args({a, crash, c, "--out-dir", out, "--summary", summary, "--resume"});
  ::setenv("KILN_TEST_ABORT_ASSET", "crash.gltf", 1);
  const command_result first = run_kiln(args);
  const command_result resumed = run_kiln(args);
  ::unsetenv("KILN_TEST_ABORT_ASSET");

  EXPECT_EQ(first.exit_code, 1) << first.stderr_text;
  const std::vector<std::string> progress = lines(first.stderr_text);
  ASSERT_EQ(progress.size(), 6u) << first.stderr_text;
  EXPECT_EQ(progress[2].rfind("kiln batch: [2/3] crash crashed ", 0), 0u) << progress[2];
  EXPECT_NE(progress[2].find("SIGABRT (signal 6)"), std::string::npos) << progress[2];
  EXPECT_EQ(progress[4].rfind("kiln batch: [3/3] c rendered ", 0), 0u) << progress[4];
  EXPECT_EQ(files_in(out), (std::vector<std::string>{"a.exr", "c.exr"}));

  // The resumed run skips the finished jobs, tries the crashed one again, and still finishes.
  EXPECT_EQ(resumed.exit_code, 1) << resumed.stderr_text;
  const json again = read_json(summary);
  EXPECT_EQ(statuses(again), (std::vector<std::string>{"skipped", "crashed", "skipped"}));
  EXPECT_EQ(again["jobs"][1]["signal"]["name"], "SIGABRT");
  EXPECT_EQ(again["jobs"][1]["signal"]["number"], SIGABRT);
  EXPECT_TRUE(again["jobs"][0]["signal"].is_null());
  EXPECT_NE(again["jobs"][1]["error"].get<std::string>().find("crashed: SIGABRT"), std::string::npos);
  EXPECT_EQ(again["totals"]["crashed"], 1);
  EXPECT_EQ(again["totals"]["skipped"], 2);
  EXPECT_EQ(again["exit_code"], 1);

  // Once the cause is gone, resuming renders only that job.
  const command_result fixed = run_kiln(args);
  EXPECT_EQ(fixed.exit_code, 0) << fixed.stderr_text;
  EXPECT_EQ(statuses(read_json(summary)), (std::vector<std::string>{"skipped", "rendered", "skipped"}));
  expect_same_pixels(out + "/a.exr", out + "/crash.exr");
}

// A folder (or a FIFO) where an asset belongs is bad input: exit 2 naming it, for render,
// compare and every way a batch takes assets, before anything is read or rendered.
TEST(batch_cli, a_folder_or_fifo_as_the_asset_is_bad_input_for_render_batch_and_compare) {
  const fs::path dir = scratch_folder("batch_folder_asset");
  copy_scene(dir / "assets/good");
  const std::string folder = (dir / "assets/folder.gltf").string();
  fs::create_directories(folder);
  const std::string fifo = (dir / "assets/pipe.gltf").string();
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const std::string out = (dir / "out").string();
  auto expect_refused = [&](const std::vector<std::string>& args, const std::string& named,
                            const std::string& kind) {
    const command_result r = run_kiln(args);
    EXPECT_EQ(r.exit_code, 2) << r.stderr_text;
    EXPECT_EQ(lines(r.stderr_text).size(), 1u) << r.stderr_text;
    EXPECT_NE(r.stderr_text.find(named + " is " + kind + ", not a glTF file"), std::string::npos)
        << r.stderr_text;
  };
  for (const auto& [path, kind] :
       {std::pair{folder, std::string("a folder")}, std::pair{fifo, std::string("a FIFO")}}) {
    // render names the file first: "kiln: PATH: a folder, not a glTF file (.gltf or .glb)".
    const command_result r =
        run_kiln({"render", path, "-o", out + "/x.exr", "--width", "8", "--height", "8"});
    EXPECT_EQ(r.exit_code, 2) << r.stderr_text;
    EXPECT_EQ(r.stderr_text, "kiln: " + path + ": " + kind + ", not a glTF file (.gltf or .glb)\n");
    const command_result c = run_kiln({"compare", path, "--width", "8", "--height", "8"});
    EXPECT_EQ(c.exit_code, 2) << c.stderr_text;
    EXPECT_EQ(c.stderr_text, "kiln: " + path + ": " + kind + ", not a glTF file (.gltf or .glb)\n");
    expect_refused(batch_args({path, "--out-dir", out, "--plan-only", (dir / "plan.json").string()}), path,
                   kind);
    expect_refused(batch_args({path, "--out-dir", out}), path, kind);
  }
  expect_refused(batch_args({(dir / "assets/*").string(), "--out-dir", out}),
                 (dir / "assets/folder.gltf").string(), "a folder");
  write_file(dir / "jobs.json", R"([{"asset": "assets/good/cornell_box.gltf"}, {"asset": "assets"}])");
  expect_refused(batch_args({"--manifest", (dir / "jobs.json").string(), "--out-dir", out}),
                 (dir / "assets").string(), "a folder");
  write_file(dir / "jobs.csv", "asset\nassets/good/cornell_box.gltf\nassets/pipe.gltf\n");
  expect_refused(batch_args({"--manifest", (dir / "jobs.csv").string(), "--out-dir", out}), fifo, "a FIFO");
  EXPECT_FALSE(fs::exists(out));
  EXPECT_FALSE(fs::exists(dir / "plan.json"));
}

// Names with spaces, quotes and any script are job names as they are (the farm takes them);
// a path with a control character or bytes that are not UTF-8 cannot pass through JSON or a
// task line, so the batch refuses it with exit 2 before anything renders.
TEST(batch_cli, names_with_spaces_are_kept_and_unprintable_paths_are_refused) {
  const fs::path dir = scratch_folder("batch_names");
  const std::string spaced = copy_scene(dir / "assets", "my shot 'v2'.gltf");
  const std::string plan = (dir / "plan.json").string(), out = (dir / "out").string();
  const command_result planned = run_kiln(batch_args({spaced, "--out-dir", out, "--plan-only", plan}));
  ASSERT_EQ(planned.exit_code, 0) << planned.stderr_text;
  EXPECT_EQ(read_json(plan)["jobs"][0]["name"], "my shot 'v2'");
  for (const std::string bad : {"tab\there.gltf", "latin1 \xe9.gltf"}) {
    const std::string asset = copy_scene(dir / "assets", bad);
    const command_result r = run_kiln(batch_args({asset, "--out-dir", out, "--plan-only", plan + "2"}));
    EXPECT_EQ(r.exit_code, 2) << r.stderr_text;
    EXPECT_EQ(lines(r.stderr_text).size(), 1u) << r.stderr_text;
    EXPECT_NE(r.stderr_text.find(bad.find('\t') != std::string::npos ? "contains a control character"
                                                                     : "is not valid UTF-8"),
              std::string::npos)
        << r.stderr_text;
    EXPECT_FALSE(fs::exists(plan + "2"));
  }
}

TEST(batch_cli, a_json_manifest_sets_each_jobs_size_samples_outputs_and_overrides) {
  const fs::path dir = scratch_folder("batch_json");
  copy_scene(dir / "scenes");
  write_file(dir / "jobs.json", R"({"defaults": {"spp": 2, "width": 16, "height": 12},
    "jobs": [
      {"asset": "scenes/cornell_box.gltf", "resolution": "40x30", "spp": 3, "output": "sub/a.exr",
       "overrides": {"max-depth": 4, "aovs": "beauty,Z"}},
      {"asset": "scenes/cornell_box.gltf", "camera": "0"}]})");
  const command_result result =
      run_kiln({"batch", "--manifest", (dir / "jobs.json").string(), "--out-dir", (dir / "out").string(),
                "-q", "--compression", "piz", "--preview", "contact.png"});
  ASSERT_EQ(result.exit_code, 0) << result.stderr_text;
  // --preview names the format only: each job's preview sits beside its EXR.
  EXPECT_EQ(files_in(dir / "out"),
            (std::vector<std::string>{"cornell_box_0.exr", "cornell_box_0.png", "sub/a.exr", "sub/a.png"}));

  const image a = read_image((dir / "out/sub/a.exr").string());
  EXPECT_EQ(a.spec.width, 40);
  EXPECT_EQ(a.spec.height, 30);
  EXPECT_EQ(a.spec.get_int_attribute("samplesPerPixel"), 3);
  EXPECT_EQ(a.spec.get_int_attribute("kiln/max_depth"), 4);
  EXPECT_EQ(attribute(a, "kiln/aovs"), "beauty,Z");
  EXPECT_EQ(a.spec.nchannels, 5);  // R G B A Z
  EXPECT_EQ(attribute(a, "kiln/scene_file"), (dir / "scenes/cornell_box.gltf").string());
  EXPECT_EQ(attribute(a, "compression"), "piz");  // the batch's storage options reach every job

  const image b = read_image((dir / "out/cornell_box_0.exr").string());
  EXPECT_EQ(b.spec.width, 16);
  EXPECT_EQ(b.spec.height, 12);
  EXPECT_EQ(b.spec.get_int_attribute("samplesPerPixel"), 2);
  EXPECT_EQ(b.spec.get_int_attribute("kiln/max_depth"), 8);
  EXPECT_EQ(attribute(b, "kiln/aovs"), "beauty,Z,N");
  // The header's command line is the `kiln render` call that reproduces the job.
  EXPECT_EQ(attribute(b, "kiln/command_line")
                .rfind("kiln render " + (dir / "scenes/cornell_box.gltf").string() + " -o " +
                           (dir / "out/cornell_box_0.exr").string() + " --width 16 --height 12 --spp 2 ",
                       0),
            0u)
      << attribute(b, "kiln/command_line");
}

TEST(batch_cli, a_csv_manifest_renders_its_rows_and_a_bad_row_stops_everything_with_exit_2) {
  const fs::path dir = scratch_folder("batch_csv");
  copy_scene(dir / "scenes");
  write_file(dir / "jobs.csv",
             "asset,resolution,spp,output,overrides\n"
             "scenes/cornell_box.gltf,20x10,5,wide.exr,\"--max-depth 2 --aovs beauty,id\"\n");
  const command_result result = run_kiln(
      {"batch", "--manifest", (dir / "jobs.csv").string(), "--out-dir", (dir / "out").string(), "-q"});
  ASSERT_EQ(result.exit_code, 0) << result.stderr_text;
  const image wide = read_image((dir / "out/wide.exr").string());
  EXPECT_EQ(wide.spec.width, 20);
  EXPECT_EQ(wide.spec.height, 10);
  EXPECT_EQ(wide.spec.get_int_attribute("samplesPerPixel"), 5);
  EXPECT_EQ(wide.spec.get_int_attribute("kiln/max_depth"), 2);
  EXPECT_EQ(attribute(wide, "kiln/aovs"), "beauty,id");

  write_file(dir / "bad.csv",
             "asset,resolution,spp,output,overrides\n"
             "scenes/cornell_box.gltf,20x10,5,one.exr,\n"
             "scenes/cornell_box.gltf,20x10,lots,two.exr,\n");
  const command_result bad =
      run_kiln({"batch", "--manifest", (dir / "bad.csv").string(), "--out-dir", (dir / "out2").string()});
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_EQ(bad.stderr_text,
            "kiln: " + (dir / "bad.csv").string() + ": line 3: spp: expected an integer, got 'lots'\n");
  EXPECT_FALSE(fs::exists(dir / "out2"));  // refused before anything rendered
}

TEST(batch_cli, resume_skips_up_to_date_outputs_and_renders_stale_or_truncated_ones) {
  const fs::path dir = scratch_folder("batch_resume");
  const std::string a = copy_scene(dir / "a", "first.gltf");
  const std::string b = copy_scene(dir / "b", "second.gltf");
  const std::string out = (dir / "out").string(), summary = (dir / "summary.json").string();
  const std::string a_exr = out + "/first.exr", b_exr = out + "/second.exr";
  auto run = [&](const std::vector<std::string>& extra = tiny) {
    const command_result r =
        run_kiln(batch_args({a, b, "--out-dir", out, "--resume", "--summary", summary, "-q"}, extra));
    EXPECT_EQ(r.exit_code, 0) << r.stderr_text;
    return statuses(read_json(summary));
  };
  EXPECT_EQ(run(), (std::vector<std::string>{"rendered", "rendered"}));  // nothing to resume from
  const image first = read_image(a_exr);
  EXPECT_EQ(attribute(first, "kiln/input_hash").size(), 16u);
  EXPECT_EQ(attribute(first, "kiln/settings_hash").size(), 16u);
  const auto a_id = identity(a_exr), b_id = identity(b_exr);

  EXPECT_EQ(run(), (std::vector<std::string>{"skipped", "skipped"}));
  EXPECT_EQ(identity(a_exr), a_id);
  EXPECT_EQ(identity(b_exr), b_id);

  // The asset changes (same scene, one more byte of JSON whitespace): only its job renders.
  std::ofstream(a, std::ios::app) << "\n";
  EXPECT_EQ(run(), (std::vector<std::string>{"rendered", "skipped"}));
  EXPECT_NE(identity(a_exr), a_id);
  EXPECT_EQ(identity(b_exr), b_id);
  EXPECT_NE(attribute(read_image(a_exr), "kiln/input_hash"), attribute(first, "kiln/input_hash"));
  EXPECT_EQ(attribute(read_image(a_exr), "kiln/settings_hash"), attribute(first, "kiln/settings_hash"));
  const auto a_id2 = identity(a_exr);

  // A truncated output (a crash mid-copy, a full disk elsewhere) reads back incomplete: rendered again.
  fs::resize_file(b_exr, fs::file_size(b_exr) / 2);
  EXPECT_EQ(run(), (std::vector<std::string>{"skipped", "rendered"}));
  EXPECT_EQ(identity(a_exr), a_id2);
  EXPECT_EQ(read_image(b_exr).spec.width, 24);
  expect_same_pixels(a_exr, b_exr);  // the same scene with the same settings

  // Other settings (more samples) make both stale.
  EXPECT_EQ(run({"--width", "24", "--height", "18", "--spp", "2"}),
            (std::vector<std::string>{"rendered", "rendered"}));
  EXPECT_EQ(read_image(a_exr).spec.get_int_attribute("samplesPerPixel"), 2);
  EXPECT_NE(attribute(read_image(a_exr), "kiln/settings_hash"), attribute(first, "kiln/settings_hash"));
  EXPECT_EQ(files_in(out), (std::vector<std::string>{"first.exr", "second.exr"}));
}

// A job is up to date only when every output it asks for is there and complete: a preview that
// is missing (deleted, newly asked for, lost between the EXR and the preview) or truncated makes
// the job render again.
TEST(batch_cli, resume_renders_a_job_whose_requested_preview_is_missing_or_incomplete) {
  const fs::path dir = scratch_folder("batch_resume_preview");
  const std::string a = copy_scene(dir / "a", "first.gltf");
  const std::string out = (dir / "out").string(), summary = (dir / "summary.json").string();
  const std::string exr = out + "/first.exr";
  auto run = [&](const std::vector<std::string>& extra) {
    std::vector<std::string> args = {a, "--out-dir", out, "--resume", "--summary", summary, "-q"};
    args.insert(args.end(), extra.begin(), extra.end());
    const command_result r = run_kiln(batch_args(args));
    EXPECT_EQ(r.exit_code, 0) << r.stderr_text;
    return statuses(read_json(summary)).at(0);
  };
  const std::vector<std::string> png = {"--preview", "p.png"}, jpeg = {"--preview", "p.jpg"};
  EXPECT_EQ(run({}), "rendered");
  EXPECT_EQ(run(png), "rendered");  // newly asked for
  ASSERT_TRUE(fs::exists(out + "/first.png"));
  EXPECT_EQ(run(png), "skipped");
  const auto id = identity(exr);
  fs::remove(out + "/first.png");  // deleted, or lost by a kill after the EXR's rename
  EXPECT_EQ(run(png), "rendered");
  EXPECT_NE(identity(exr), id);
  ASSERT_TRUE(fs::exists(out + "/first.png"));
  fs::resize_file(out + "/first.png", fs::file_size(out + "/first.png") - 20);
  EXPECT_EQ(run(png), "rendered");
  EXPECT_EQ(run(png), "skipped");
  EXPECT_EQ(run(jpeg), "rendered");
  EXPECT_EQ(run(jpeg), "skipped");
  fs::resize_file(out + "/first.jpg",
                  fs::file_size(out + "/first.jpg") - 2);  // a JPEG cut short decodes grey
  EXPECT_EQ(run(jpeg), "rendered");
  EXPECT_EQ(run(jpeg), "skipped");
  // A preview of another size (an older, larger render under the same name) is not this job's.
  const command_result big = run_kiln({"render", a, "-o", (dir / "big.exr").string(), "--width", "30",
                                       "--height", "20", "-q", "--preview", out + "/first.jpg"});
  ASSERT_EQ(big.exit_code, 0) << big.stderr_text;
  EXPECT_EQ(run(jpeg), "rendered");
  EXPECT_EQ(run({}), "skipped");  // no preview asked for: the EXR alone decides
}

struct timed_line {
  double at = 0.0;  // seconds after the start
  std::string text;
};

// Runs kiln with stderr into a pipe (not a terminal) and stamps each line as it arrives;
// seconds is the whole run.
std::vector<timed_line> run_kiln_timed(const std::vector<std::string>& args, double& seconds) {
  auto quote = [](const std::string& text) {
    std::string out = "'";
    for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
  };
  std::string command = quote(KILN_BINARY);
  for (const std::string& a : args) command += " " + quote(a);
  command += " 2>&1 >/dev/null </dev/null";
  const auto start = std::chrono::steady_clock::now();
  auto since = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  std::vector<timed_line> out;
  FILE* pipe = ::popen(command.c_str(), "r");
  EXPECT_NE(pipe, nullptr);
  if (!pipe) return out;
  char buffer[4096];
  while (std::fgets(buffer, sizeof buffer, pipe)) {
    std::string text = buffer;
    if (!text.empty() && text.back() == '\n') text.pop_back();
    out.push_back({since(), text});
  }
  EXPECT_EQ(::pclose(pipe), 0);
  seconds = since();
  return out;
}

// A wall that fills the view: every pixel costs the same, so the work done predicts the rest.
std::string write_uniform_scene(const fs::path& path) {
  testing::gltf_builder b;
  const int material =
      b.add_material({{"pbrMetallicRoughness", {{"baseColorFactor", {0.8, 0.8, 0.8, 1.0}}}}});
  const int mesh =
      b.add_mesh({{-50, -50, 0}, {50, -50, 0}, {50, 50, 0}, {-50, 50, 0}}, {0, 1, 2, 0, 2, 3}, material);
  b.add_node({{"mesh", mesh}});
  b.write(path.string());
  return path.string();
}

// Off a terminal, a render prints a progress line every --progress-interval with an ETA from the
// work done; the first ETA is within a factor of 3 of the time that really remained. In a batch
// the job's lines (progress and messages) come prefixed with the job.
TEST(batch_cli, progress_lines_reach_a_log_with_sane_etas_and_batch_lines_name_their_job) {
  const fs::path dir = scratch_folder("batch_progress");
  const std::string asset = write_uniform_scene(dir / "uniform.gltf");
  const std::vector<std::string> view = {"--look-from",
                                         "0,0,5",
                                         "--look-at",
                                         "0,0,0",
                                         "--width",
                                         "160",
                                         "--height",
                                         "120",
                                         "--spp",
                                         "400",
                                         "--threads",
                                         "2",
                                         "--progress-interval",
                                         "0.5"};
  std::vector<std::string> render = {"render", asset, "-o", (dir / "u.exr").string()};
  render.insert(render.end(), view.begin(), view.end());
  double seconds = 0.0;
  const std::vector<timed_line> got = run_kiln_timed(render, seconds);
  const std::regex line(R"(kiln: rendering +(\d+)%  ETA (\d+\.\d) s)");
  std::vector<std::pair<double, double>> etas;  // (arrived, ETA)
  int last_percent = -1;
  for (const timed_line& l : got) {
    std::smatch m;
    if (l.text.rfind("kiln: rendering ", 0) != 0) continue;
    ASSERT_TRUE(std::regex_match(l.text, m, line)) << l.text;
    const int percent = std::stoi(m[1]);
    EXPECT_GE(percent, last_percent);
    EXPECT_LT(percent, 100);
    last_percent = percent;
    etas.push_back({l.at, std::stod(m[2])});
  }
  ASSERT_GE(etas.size(), 2u) << "render took " << seconds << " s";
  const double remaining = seconds - etas[0].first;
  EXPECT_LE(etas[0].second, 3.0 * remaining)
      << "first ETA " << etas[0].second << " s, " << remaining << " s remained";
  EXPECT_GE(etas[0].second, remaining / 3.0)
      << "first ETA " << etas[0].second << " s, " << remaining << " s remained";

  std::vector<std::string> batch = {"batch", asset, "--out-dir", (dir / "out").string()};
  batch.insert(batch.end(), view.begin(), view.end());
  const std::vector<timed_line> batch_lines = run_kiln_timed(batch, seconds);
  size_t progress_lines = 0;
  for (const timed_line& l : batch_lines) {
    EXPECT_EQ(l.text.rfind("kiln batch: ", 0), 0u) << l.text;
    if (l.text.rfind("kiln batch: [1/1] uniform: rendering ", 0) == 0) ++progress_lines;
  }
  EXPECT_GE(progress_lines, 2u);
  ASSERT_FALSE(batch_lines.empty());
  // The asset has no lights: under --lighting headlight the render's note about it names the job.
  const std::vector<timed_line> noted =
      run_kiln_timed({"batch", asset, "--out-dir", (dir / "noted").string(), "--width", "8", "--height", "8",
                      "--lighting", "headlight"},
                     seconds);
  ASSERT_FALSE(noted.empty());
  EXPECT_EQ(noted[0].text,
            "kiln batch: [1/1] uniform: the file has no lights; using a headlight at the camera");
}

TEST(batch_cli, a_plan_job_rendered_by_hand_gives_the_batchs_pixels_and_hashes) {
  const fs::path dir = scratch_folder("batch_plan");
  const std::string asset = copy_scene(dir / "scenes");
  const std::string out = (dir / "out").string(), plan_path = (dir / "plan.json").string();
  const std::vector<std::string> options = {"--width", "32", "--height", "24",
                                            "--spp",   "2",  "--aovs",   "beauty,N,id"};
  write_file(dir / "jobs.json",
             R"([{"asset": "scenes/cornell_box.gltf", "camera": "0", "overrides": {"max-depth": 3}}])");
  const std::vector<std::string> inputs = {asset,       "--manifest", (dir / "jobs.json").string(),
                                           "--out-dir", out,          "-q"};
  command_result planned = run_kiln(batch_args(inputs, [&] {
    std::vector<std::string> a = options;
    a.insert(a.end(), {"--plan-only", plan_path});
    return a;
  }()));
  ASSERT_EQ(planned.exit_code, 0) << planned.stderr_text;
  EXPECT_FALSE(fs::exists(out));  // nothing rendered

  const json plan = read_json(plan_path);
  EXPECT_EQ(plan["version"], 1);
  ASSERT_EQ(plan["jobs"].size(), 2u);
  const json& plain = plan["jobs"][0];
  const json& camera = plan["jobs"][1];
  EXPECT_EQ(plain["name"], "cornell_box");
  EXPECT_EQ(camera["name"], "cornell_box_0");
  EXPECT_EQ(plain["asset"], asset);
  EXPECT_EQ(camera["asset"], asset);
  EXPECT_EQ(plain["output"], out + "/cornell_box.exr");
  EXPECT_EQ(camera["output"], out + "/cornell_box_0.exr");
  // Each job's estimate for the farm (job/plan_estimate.h): a probe no larger than the frame, a
  // render time, and a peak that holds at least the film (32 bytes a pixel).
  for (const json& job : plan["jobs"]) {
    ASSERT_TRUE(job.contains("estimate")) << job.dump();
    const json& e = job["estimate"];
    EXPECT_GT(e["render_seconds"].get<double>(), 0.0);
    EXPECT_GE(e["seconds"].get<double>(), e["render_seconds"].get<double>());
    EXPECT_GE(e["peak_memory_bytes"].get<uint64_t>(), uint64_t(32) * 32 * 24);
    EXPECT_LE(e["probe"][0].get<int>(), 32);
    EXPECT_EQ(e["probe"][2], 2);
  }
  // --no-estimates leaves them out, and nothing else.
  const std::string bare_path = (dir / "bare.json").string();
  command_result bare = run_kiln(batch_args(inputs, [&] {
    std::vector<std::string> a = options;
    a.insert(a.end(), {"--plan-only", bare_path, "--no-estimates"});
    return a;
  }()));
  ASSERT_EQ(bare.exit_code, 0) << bare.stderr_text;
  json stripped = plan;
  for (json& job : stripped["jobs"]) job.erase("estimate");
  EXPECT_EQ(read_json(bare_path), stripped);
  // The value after each option name, or "" when the option is absent.
  auto value = [](const json& job, const std::string& name) -> std::string {
    const std::vector<std::string> args = job["render_args"];
    auto it = std::find(args.begin(), args.end(), name);
    return it == args.end() || it + 1 == args.end() ? "" : *(it + 1);
  };
  EXPECT_EQ(value(camera, "--width"), "32");
  EXPECT_EQ(value(camera, "--height"), "24");
  EXPECT_EQ(value(camera, "--spp"), "2");
  EXPECT_EQ(value(camera, "--camera"), "0");
  EXPECT_EQ(value(camera, "--max-depth"), "3");
  EXPECT_EQ(value(plain, "--max-depth"), "8");
  EXPECT_EQ(value(camera, "--aovs"), "beauty,N,id");
  for (const char* absent : {"-o", "--output", "--band", "--crop", "--out-dir", "-q"})
    EXPECT_EQ(value(camera, absent), "") << absent;
  for (const json& arg : camera["render_args"]) EXPECT_NE(arg.get<std::string>(), asset);

  const command_result batch = run_kiln(batch_args(inputs, options));
  ASSERT_EQ(batch.exit_code, 0) << batch.stderr_text;
  std::vector<std::string> by_hand = {"render", camera["asset"], "-o", (dir / "by_hand.exr").string(), "-q"};
  for (const json& arg : camera["render_args"]) by_hand.push_back(arg);
  const command_result hand = run_kiln(by_hand);
  ASSERT_EQ(hand.exit_code, 0) << hand.stderr_text;
  expect_same_pixels(camera["output"], (dir / "by_hand.exr").string());
  const image batch_image = read_image(camera["output"]),
              hand_image = read_image((dir / "by_hand.exr").string());
  EXPECT_EQ(attribute(hand_image, "kiln/settings_hash").size(), 16u);  // kiln render records both hashes too
  EXPECT_EQ(attribute(hand_image, "kiln/input_hash").size(), 16u);
  EXPECT_EQ(attribute(hand_image, "kiln/settings_hash"), attribute(batch_image, "kiln/settings_hash"));
  EXPECT_EQ(attribute(hand_image, "kiln/input_hash"), attribute(batch_image, "kiln/input_hash"));
  EXPECT_EQ(attribute(hand_image, "kiln/camera"), attribute(batch_image, "kiln/camera"));
  // The two jobs differ in camera and depth, so their settings (and pixels) are not the same.
  EXPECT_NE(attribute(read_image(plain["output"]), "kiln/settings_hash"),
            attribute(batch_image, "kiln/settings_hash"));
}

}  // namespace
}  // namespace kiln
