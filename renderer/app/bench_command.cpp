#include "app/bench_command.h"

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "accel/embree/embree_accelerator.h"
#include "app/interrupt.h"
#include "app/text_output.h"
#include "io/exr/exr_writer.h"
#include "job/render_sequence.h"
#include "ray_replay/bench_run.h"

namespace kiln {

namespace {

std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);)
    if (line.rfind("model name", 0) == 0) {
      const size_t colon = line.find(':');
      if (colon != std::string::npos) return line.substr(line.find_first_not_of(' ', colon + 1));
    }
  return "unknown";
}

std::string host_name() {
  char name[256] = {};
  return ::gethostname(name, sizeof(name) - 1) == 0 ? std::string(name) : std::string("unknown");
}

double mrays(size_t rays, double seconds) { return seconds > 0.0 ? double(rays) / seconds / 1e6 : 0.0; }

// The headline ratio: kiln's whole render (shading included) against the bare loop over the same
// rays, both as rays per second.
struct totals {
  size_t rays = 0;
  double bare_seconds = 0.0;
  double kiln_seconds = 0.0;
};

totals sum_kinds(const bench_measurement& m, bool camera_and_shadow_only) {
  totals t;
  for (const kind_measurement& k : m.kinds) {
    if (k.replayed_as_occlusion) continue;  // the render traced these rays once, as closest-hit queries
    if (camera_and_shadow_only && k.kind != "camera" && k.kind != "shadow") continue;
    t.rays += k.rays;
    t.bare_seconds += k.bare_seconds;
    t.kiln_seconds += k.kiln_seconds;
  }
  return t;
}

nlohmann::json report_json(const bench_options& o, const prepared_scene& p, const bench_measurement& m,
                           const std::string& label, size_t rss_before_load) {
  nlohmann::json kinds = nlohmann::json::array();
  for (const kind_measurement& k : m.kinds) {
    kinds.push_back({{"kind", k.kind},
                     {"query", k.query},
                     {"rays", k.rays},
                     {"bare_embree_mrays_per_s", mrays(k.rays, k.bare_seconds)},
                     {"kiln_query_mrays_per_s", mrays(k.rays, k.kiln_seconds)},
                     {"kiln_query_over_bare", k.kiln_seconds > 0 ? k.bare_seconds / k.kiln_seconds : 0.0},
                     {"hits", k.kiln_hits}});
    if (k.bare_stream_seconds > 0.0) {
      nlohmann::json& j = kinds.back();
      j["bare_stream_mrays_per_s"] = mrays(k.rays, k.bare_stream_seconds);
      j["kiln_stream_mrays_per_s"] = mrays(k.rays, k.kiln_stream_seconds);
      j["bare_stream_over_bare"] = k.bare_seconds / k.bare_stream_seconds;
      j["kiln_stream_over_bare"] = k.kiln_stream_seconds > 0 ? k.bare_seconds / k.kiln_stream_seconds : 0.0;
    }
    if (k.kiln_batch_seconds > 0.0) {
      nlohmann::json& j = kinds.back();
      j["kiln_batch_mrays_per_s"] = mrays(k.rays, k.kiln_batch_seconds);
      j["kiln_batch_over_bare"] = k.bare_seconds / k.kiln_batch_seconds;
      j["kiln_batch_over_single"] = k.kiln_seconds / k.kiln_batch_seconds;
      j["batch_hits"] = k.kiln_batch_hits;
      if (k.replayed_as_occlusion) j["replayed_as_occlusion"] = true;
    }
  }
  const totals all = sum_kinds(m, false);
  const size_t traced = all.rays;
  return {{"label", label},
          {"scene_file", o.view.input},
          {"kiln_version", KILN_VERSION},
          {"embree_version", embree_version()},
          {"machine",
           {{"hostname", host_name()},
            {"cpu", cpu_model()},
            {"logical_cores", std::thread::hardware_concurrency()}}},
          {"threads", m.threads},
          {"accel", o.accel},
          {"bvh_quality", bvh_quality_name(o.view.embree.quality)},
          {"bvh_compact", o.view.embree.compact},
          {"packets", o.view.packets},
          {"camera", p.camera_description},
          {"width", p.cam.width},
          {"height", p.cam.height},
          {"samples_per_pixel", samples_per_pixel_of(o.view)},
          {"repeats", o.repeats},
          {"triangles", {{"unique", m.unique_triangles}, {"placed", m.placed_triangles}}},
          {"instances", m.instances},
          {"load_seconds", p.load_seconds},
          {"build_seconds", m.build_seconds},
          {"first_pixel_seconds", p.load_seconds + m.build_seconds},
          {"render_seconds", m.render_seconds},
          {"render_cpu_seconds", m.render_cpu_seconds},
          {"peak_rss_bytes",
           {{"after_build", m.peak_rss_after_build}, {"after_render", m.peak_rss_after_render}}},
          {"rss_bytes", {{"before_load", rss_before_load}, {"after_build", m.rss_after_build}}},
          {"scene_memory_bytes", m.rss_after_build - std::min(m.rss_after_build, rss_before_load)},
          {"build_rss_delta_bytes", m.rss_build_delta},
          {"embree_bytes", {{"after_build", m.embree_bytes}, {"peak", m.embree_peak_bytes}}},
          {"rays",
           {{"camera", m.rays.camera},
            {"shadow", m.rays.shadow},
            {"reflection", m.rays.reflection},
            {"refraction", m.rays.refraction},
            {"transparency", m.rays.transparency},
            {"queries", traced}}},
          {"render_mrays_per_s", mrays(traced, m.render_seconds)},
          {"bare_embree_mrays_per_s", mrays(traced, all.bare_seconds)},
          {"render_over_bare", m.render_seconds > 0 ? all.bare_seconds / m.render_seconds : 0.0},
          {"kinds", kinds}};
}

std::string report_csv(const nlohmann::json& r) {
  std::ostringstream out;
  out << "label,accel,threads,width,height,spp,kind,query,rays,bare_embree_mrays_per_s,kiln_mrays_per_s,"
         "kiln_over_bare,load_s,build_s,render_s,peak_rss_mb,bvh_quality,bvh_compact,packets,embree_mb\n";
  auto row = [&](const std::string& kind, const std::string& query, const nlohmann::json& rays,
                 const nlohmann::json& bare, const nlohmann::json& kiln, const nlohmann::json& ratio) {
    out << r["label"].get<std::string>() << ',' << r["accel"].get<std::string>() << ',' << r["threads"] << ','
        << r["width"] << ',' << r["height"] << ',' << r["samples_per_pixel"] << ',' << kind << ',' << query
        << ',' << rays << ',' << bare << ',' << kiln << ',' << ratio << ',' << r["load_seconds"] << ','
        << r["build_seconds"] << ',' << r["render_seconds"] << ','
        << double(r["peak_rss_bytes"]["after_render"].get<size_t>()) / 1e6 << ','
        << r["bvh_quality"].get<std::string>() << ',' << r["bvh_compact"] << ',' << r["packets"] << ','
        << double(r["embree_bytes"]["after_build"].get<size_t>()) / 1e6 << '\n';
  };
  for (const auto& k : r["kinds"]) {
    row(k["kind"], k["query"], k["rays"], k["bare_embree_mrays_per_s"], k["kiln_query_mrays_per_s"],
        k["kiln_query_over_bare"]);
    if (k.contains("bare_stream_mrays_per_s"))
      row(k["kind"], "intersect_stream", k["rays"], k["bare_stream_mrays_per_s"],
          k["kiln_stream_mrays_per_s"], k["kiln_stream_over_bare"]);
    if (k.contains("kiln_batch_mrays_per_s"))
      row(k["kind"], "occluded_batch", k["rays"], k["bare_embree_mrays_per_s"], k["kiln_batch_mrays_per_s"],
          k["kiln_batch_over_bare"]);
  }
  row("render", "all", r["rays"]["queries"], r["bare_embree_mrays_per_s"], r["render_mrays_per_s"],
      r["render_over_bare"]);
  return out.str();
}

void print_summary(const nlohmann::json& r) {
  std::printf(
      "%s: %dx%d, %d spp, %d threads, %s (bvh %s%s, packets %s) | load %.3f s, build %.3f s, render %.3f s | "
      "peak RSS %.1f MB, Embree %.1f MB\n",
      r["label"].get<std::string>().c_str(), r["width"].get<int>(), r["height"].get<int>(),
      r["samples_per_pixel"].get<int>(), r["threads"].get<int>(), r["accel"].get<std::string>().c_str(),
      r["bvh_quality"].get<std::string>().c_str(), r["bvh_compact"].get<bool>() ? ", compact" : "",
      r["packets"].get<bool>() ? "on" : "off", r["load_seconds"].get<double>(),
      r["build_seconds"].get<double>(), r["render_seconds"].get<double>(),
      double(r["peak_rss_bytes"]["after_render"].get<size_t>()) / 1e6,
      double(r["embree_bytes"]["after_build"].get<size_t>()) / 1e6);
  std::printf("  %-12s %-9s %10s %14s %14s %8s\n", "kind", "query", "rays", "bare Mrays/s", "kiln Mrays/s",
              "ratio");
  for (const auto& k : r["kinds"]) {
    std::printf("  %-12s %-9s %10zu %14.2f %14.2f %8.3f%s\n", k["kind"].get<std::string>().c_str(),
                k["query"].get<std::string>().c_str(), k["rays"].get<size_t>(),
                k["bare_embree_mrays_per_s"].get<double>(), k["kiln_query_mrays_per_s"].get<double>(),
                k["kiln_query_over_bare"].get<double>(),
                k.contains("replayed_as_occlusion") ? "   (walked shadow rays, as occlusion queries)" : "");
    if (k.contains("bare_stream_mrays_per_s"))
      std::printf("  %-12s %-9s %10zu %14.2f %14.2f %8.3f   (streams; ratio to the bare single-ray loop)\n",
                  k["kind"].get<std::string>().c_str(), "stream", k["rays"].get<size_t>(),
                  k["bare_stream_mrays_per_s"].get<double>(), k["kiln_stream_mrays_per_s"].get<double>(),
                  k["kiln_stream_over_bare"].get<double>());
    if (k.contains("kiln_batch_mrays_per_s"))
      std::printf("  %-12s %-9s %10zu %14.2f %14.2f %8.3f   (occluded_batch: %.2fx the single-ray query)\n",
                  k["kind"].get<std::string>().c_str(), "batch", k["rays"].get<size_t>(),
                  k["bare_embree_mrays_per_s"].get<double>(), k["kiln_batch_mrays_per_s"].get<double>(),
                  k["kiln_batch_over_bare"].get<double>(), k["kiln_batch_over_single"].get<double>());
  }
  std::printf("  %-12s %-9s %10zu %14.2f %14.2f %8.3f   (whole render, shading included)\n", "render", "all",
              r["rays"]["queries"].get<size_t>(), r["bare_embree_mrays_per_s"].get<double>(),
              r["render_mrays_per_s"].get<double>(), r["render_over_bare"].get<double>());
}

}  // namespace

void add_bench_options(CLI::App& app, bench_options& o) {
  add_view_options(app, o.view);
  app.add_option("--accel", o.accel, "Backend of the timed render (the bare loop is always Embree)")
      ->check(CLI::IsMember({"embree", "grid", "adaptive-grid"}))
      ->capture_default_str();
  app.add_option("--repeat", o.repeats, "Timed renders and replays; the fastest is reported")
      ->check(CLI::Range(1, 100))
      ->capture_default_str();
  app.add_option("--json", o.json, "Write the measurements as JSON");
  app.add_option("--csv", o.csv,
                 "Write the measurements as CSV (one row per ray kind, plus the whole render)");
  app.add_option("--label", o.label, "Name of this case in the reports (default: the asset's file name)");
  app.add_option(
      "--frames", o.frames,
      "Time a sequence instead (FIRST-LAST[:STEP]): each frame's posing, backend update and render, "
      "and the per-frame overhead of posing and updating against the render");
}

namespace {

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

// --frames: renders the sequence (nothing written) and reports, over the frames after the first
// (those that update the backend rather than build it), the median posing, update and render
// times and the overhead (posing + update) / render.
void run_sequence_bench(const bench_options& o) {
  render_job job;
  job.options = o.view;
  job.options.frames = o.frames;
  job.options.output.clear();
  job.cancel = &interrupt_requested();
  nlohmann::json frames = nlohmann::json::array();
  std::vector<double> pose, update, render, overhead;
  double first_build = 0.0;
  run_sequence(job, [&](const render_job_result& result, const render_options&, const frame_report& made) {
    frames.push_back({{"frame", made.frame},
                      {"pose_seconds", made.pose_seconds},
                      {"backend_seconds", made.update_seconds},
                      {"backend_updated", made.backend_updated},
                      {"textures_kept", made.textures_kept},
                      {"environment_kept", made.environment_kept},
                      {"render_seconds", result.stats.seconds}});
    if (frames.size() == 1) {
      first_build = made.update_seconds;
      return;
    }
    pose.push_back(made.pose_seconds);
    update.push_back(made.update_seconds);
    render.push_back(result.stats.seconds);
    overhead.push_back((made.pose_seconds + made.update_seconds) / std::max(result.stats.seconds, 1e-9));
  });
  const std::string label =
      o.label.empty() ? std::filesystem::path(o.view.input).filename().string() : o.label;
  const nlohmann::json report = {{"label", label},
                                 {"frames", frames},
                                 {"threads", o.view.threads},
                                 {"first_frame_backend_build_seconds", first_build},
                                 {"median_pose_seconds", median(pose)},
                                 {"median_backend_update_seconds", median(update)},
                                 {"median_render_seconds", median(render)},
                                 {"median_overhead", median(overhead)}};
  if (!o.json.empty()) write_text_atomically(o.json, report.dump(2) + "\n");
  if (!o.view.quiet)
    std::printf(
        "%s: %zu frames; after the first: pose %.2f ms, backend update %.2f ms (first frame's build %.2f "
        "ms), "
        "render %.2f ms (medians); overhead (pose + update) / render %.1f%%\n",
        label.c_str(), frames.size(), 1e3 * median(pose), 1e3 * median(update), 1e3 * first_build,
        1e3 * median(render), 100.0 * median(overhead));
}

}  // namespace

void run_bench_command(const bench_options& o) {
  if (!o.json.empty()) check_output_writable(o.json);
  if (!o.frames.empty()) {
    if (!o.csv.empty()) throw input_error("", "--csv", "a --frames bench writes --json only");
    return run_sequence_bench(o);
  }
  if (!o.csv.empty()) check_output_writable(o.csv);
  // The process's own baseline (libraries, thread pools) before anything of the scene exists, so the
  // report can give the memory the scene, its BVH and the render added.
  const size_t rss_before_load = current_resident_bytes();
  prepared_scene prepared = prepare_cli_scene(o.view);
  bench_settings settings;
  settings.accel = o.accel;
  settings.repeats = o.repeats;
  settings.embree = o.view.embree;
  render_settings render = make_render_settings(o.view);
  render.cancel = &interrupt_requested();
  const bench_measurement m = run_bench(prepared.world, prepared.cam, render, settings);
  const std::string label =
      o.label.empty() ? std::filesystem::path(o.view.input).filename().string() : o.label;
  const nlohmann::json report = report_json(o, prepared, m, label, rss_before_load);
  if (!o.json.empty()) write_text_atomically(o.json, report.dump(2) + "\n");
  if (!o.csv.empty()) write_text_atomically(o.csv, report_csv(report));
  if (!o.view.quiet) print_summary(report);
}

}  // namespace kiln
