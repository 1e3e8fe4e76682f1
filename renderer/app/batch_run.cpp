#include "app/batch_run.h"

#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>

#include "app/interrupt.h"
#include "app/render_fingerprint.h"
#include "app/text_output.h"
#include "core/error.h"
#include "io/exr/exr_reader.h"

namespace kiln {

namespace {

namespace fs = std::filesystem;

const char* status_name(job_status s) {
  switch (s) {
    case job_status::rendered:
      return "rendered";
    case job_status::skipped:
      return "skipped";
    case job_status::failed:
      return "failed";
    case job_status::interrupted:
      return "interrupted";
    case job_status::not_started:
      return "not_started";
  }
  return "?";
}

struct job_result {
  job_status status = job_status::not_started;
  std::string error;
  double seconds = 0.0;
};

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Renders (or skips) one job; every failure becomes the job's error, only a signal escapes.
job_result run_job(const batch_job& job, bool resume) {
  job_result result;
  const auto start = std::chrono::steady_clock::now();
  try {
    if (!job.error.empty()) throw input_error("", job.where, job.error);
    const render_fingerprint fingerprint = make_fingerprint(job.options);
    if (resume && output_up_to_date(job.options.output, fingerprint)) {
      result.status = job_status::skipped;
    } else {
      std::error_code ec;
      fs::create_directories(fs::path(job.options.output).parent_path(), ec);
      run_render(job.options, &fingerprint);
      result.status = job_status::rendered;
    }
  } catch (const error& e) {
    result.status = e.kind() == error_kind::interrupted ? job_status::interrupted : job_status::failed;
    result.error = e.what();
  } catch (const std::bad_alloc&) {
    result.status = job_status::failed;
    result.error = "out of memory";
  } catch (const std::exception& e) {
    result.status = job_status::failed;
    result.error = e.what();
  }
  result.seconds = seconds_since(start);
  return result;
}

nlohmann::json summary_json(const std::vector<batch_job>& jobs, const std::vector<job_result>& results,
                            int exit_code, double seconds) {
  nlohmann::json list = nlohmann::json::array();
  std::map<std::string, int> counts{
      {"rendered", 0}, {"skipped", 0}, {"failed", 0}, {"interrupted", 0}, {"not_started", 0}};
  for (size_t i = 0; i < jobs.size(); ++i) {
    const job_result& r = results[i];
    ++counts[status_name(r.status)];
    list.push_back({{"name", jobs[i].name},
                    {"asset", jobs[i].options.input},
                    {"output", jobs[i].options.output},
                    {"status", status_name(r.status)},
                    {"error", r.error.empty() ? nlohmann::json(nullptr) : nlohmann::json(r.error)},
                    {"seconds", r.seconds}});
  }
  nlohmann::json totals = {{"jobs", jobs.size()}, {"seconds", seconds}};
  for (const auto& [name, count] : counts) totals[name] = count;
  return {{"version", 1}, {"exit_code", exit_code}, {"jobs", list}, {"totals", totals}};
}

}  // namespace

bool output_up_to_date(const std::string& output, const render_fingerprint& fingerprint) {
  std::error_code ec;
  if (!fs::is_regular_file(output, ec)) return false;
  try {
    const exr_image image = read_exr(output);  // every pixel: a truncated file fails here
    return exr_string_attribute(image, "kiln/input_hash") == fingerprint.input_hash &&
           exr_string_attribute(image, "kiln/settings_hash") == fingerprint.settings_hash;
  } catch (const error&) {
    return false;
  }
}

int run_batch_jobs(const std::vector<batch_job>& jobs, bool resume, const std::string& summary, bool quiet) {
  const auto batch_start = std::chrono::steady_clock::now();
  std::vector<job_result> results(jobs.size());
  size_t done = 0, rendered = 0, failed = 0;
  double render_seconds = 0.0;
  bool interrupted = false;
  for (size_t i = 0; i < jobs.size() && !interrupted; ++i) {
    if (interrupt_requested()) break;  // a signal between jobs: the rest are not started
    results[i] = run_job(jobs[i], resume);
    const job_result& r = results[i];
    interrupted = r.status == job_status::interrupted;
    ++done;
    if (r.status == job_status::rendered) {
      ++rendered;
      render_seconds += r.seconds;
    }
    if (r.status == job_status::failed) ++failed;
    if (quiet) continue;
    std::fprintf(stderr, "kiln batch: [%zu/%zu] %s %s %.2f s%s%s\n", i + 1, jobs.size(), jobs[i].name.c_str(),
                 status_name(r.status), r.seconds, r.error.empty() ? "" : ": ", r.error.c_str());
    // ETA from the mean time of a rendered job: skipped ones cost next to nothing.
    const size_t left = jobs.size() - done;
    if (interrupted)
      std::fprintf(stderr, "kiln batch: stopped by signal %d, %zu job%s not started\n", interrupt_signal(),
                   left, left == 1 ? "" : "s");
    else if (rendered)
      std::fprintf(stderr, "kiln batch: %zu/%zu done, %zu failed, ETA %.1f s\n", done, jobs.size(), failed,
                   render_seconds / double(rendered) * double(left));
    else
      std::fprintf(stderr, "kiln batch: %zu/%zu done, %zu failed, ETA unknown\n", done, jobs.size(), failed);
  }
  if (interrupt_requested()) interrupted = true;
  const int exit_code = interrupted ? 128 + (interrupt_signal() ? interrupt_signal() : SIGINT)
                        : failed    ? 1
                                    : 0;
  if (!summary.empty()) {
    try {
      write_text_atomically(
          summary, summary_json(jobs, results, exit_code, seconds_since(batch_start)).dump(2) + "\n");
    } catch (const error& e) {
      std::fprintf(stderr, "kiln: %s\n", e.what());
      return exit_code ? exit_code : 1;
    }
  }
  return exit_code;
}

}  // namespace kiln
