#include "app/batch_run.h"

#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>

#include "app/batch_child.h"
#include "app/exit_status.h"
#include "app/interrupt.h"
#include "app/text_output.h"
#include "core/error.h"
#include "core/memory_budget.h"
#include "io/exr/contact_sheet.h"
#include "io/exr/exr_verify.h"
#include "io/exr/preview_record.h"
#include "job/deep_output.h"
#include "job/render_fingerprint.h"
#include "job/render_job.h"

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
    case job_status::crashed:
      return "crashed";
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
  std::string resume;  // with --resume, why an existing output was not kept (rendered again)
  int signal = 0;      // crashed: the signal that killed the job's process
  double seconds = 0.0;
};

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

bool is_interrupt(int signo) { return signo == SIGINT || signo == SIGTERM; }

// Renders (or skips) one job in its own process; every failure, a crash included, becomes the
// job's status and error.
job_result run_job(const batch_job& job, bool resume, const std::string& label, bool quiet) {
  job_result result;
  const auto start = std::chrono::steady_clock::now();
  const render_options options = batch_job_options(job);
  try {
    if (!job.entry->error.empty()) throw input_error("", job.entry->where, job.entry->error);
    std::error_code ec;
    if (resume && fs::exists(options.output, ec)) {
      memory_budget budget(job_memory_limit(options));
      result.resume = resume_problem(options, make_fingerprint(options, &interrupt_requested()), &budget);
      if (result.resume.empty()) {
        result.status = job_status::skipped;
        result.seconds = seconds_since(start);
        return result;
      }
    }
  } catch (const std::exception& e) {
    result.status = job_status::failed;
    result.error = e.what();
    result.seconds = seconds_since(start);
    return result;
  }
  std::error_code ec;
  fs::create_directories(fs::path(options.output).parent_path(), ec);
  const child_outcome child = run_job_in_child(options, label, quiet);
  result.seconds = seconds_since(start);
  result.error = child.error;
  if (!child.started) {
    result.status = interrupt_requested() ? job_status::not_started : job_status::failed;
  } else if (child.signal) {
    // A second SIGINT/SIGTERM kills the child on purpose; any other signal is a crash.
    if (interrupt_requested() && is_interrupt(child.signal)) {
      result.status = job_status::interrupted;
      result.error = "render interrupted, nothing written";
    } else {
      result.status = job_status::crashed;
      result.signal = child.signal;
      result.error = "crashed: " + signal_name(child.signal) + " (signal " + std::to_string(child.signal) +
                     ")" + (child.error.empty() ? "" : "; last message: " + child.error);
    }
  } else if (child.exit_code == 0) {
    result.status = job_status::rendered;
  } else if (interrupt_requested() && child.exit_code > 128 && is_interrupt(child.exit_code - 128)) {
    result.status = job_status::interrupted;
  } else {
    result.status = job_status::failed;
    if (result.error.empty())
      result.error = "the job's process exited with " + std::to_string(child.exit_code);
  }
  return result;
}

// The summary's entry of job i.
nlohmann::json summary_entry(const batch_job& job, const job_result& r) {
  return {{"name", job.name},
          {"asset", job.entry->options.input},
          {"output", batch_job_output(job)},
          {"status", status_name(r.status)},
          {"error", r.error.empty() ? nlohmann::json(nullptr) : nlohmann::json(r.error)},
          {"resume", r.resume.empty() ? nlohmann::json(nullptr) : nlohmann::json(r.resume)},
          {"signal", r.signal ? nlohmann::json{{"number", r.signal}, {"name", signal_name(r.signal)}}
                              : nlohmann::json(nullptr)},
          {"seconds", r.seconds}};
}

}  // namespace

std::string resume_problem(const render_options& options, const render_fingerprint& fingerprint,
                           memory_budget* budget) {
  const expected_attributes hashes = {{"kiln/input_hash", fingerprint.input_hash},
                                      {"kiln/settings_hash", fingerprint.settings_hash}};
  const exr_check flat = check_flat_exr(options.output, hashes, budget);
  if (!flat.problem.empty()) return options.output + ": " + flat.problem;
  // The deep file is renamed into place before the EXR, and the preview after it.
  if (options.deep) {
    const std::string path = deep_output_path(options.output);
    const exr_check deep = check_deep_exr(path, hashes, budget);
    if (!deep.problem.empty()) return path + ": " + deep.problem;
    if (!(deep.data_window == flat.data_window) || !(deep.display_window == flat.display_window))
      return path + ": its windows are not the EXR's";
  }
  if (!options.preview.empty()) {
    const std::string problem =
        preview_file_problem(options.preview, flat.data_window.width(), flat.data_window.height());
    if (!problem.empty()) return options.preview + ": " + problem;
  }
  return "";
}

namespace {

// The contact sheet of a batch that ran to its end: each job's EXR (rendered or skipped as up to
// date) under its name, failed and crashed jobs marked.
void write_batch_contact_sheet(const std::string& path, const std::vector<batch_job>& jobs,
                               const std::vector<job_result>& results) {
  std::vector<contact_sheet_cell> cells;
  for (size_t i = 0; i < jobs.size(); ++i) {
    contact_sheet_cell cell;
    cell.label = jobs[i].name;
    cell.exposure = jobs[i].entry->options.preview_exposure;
    const job_status status = results[i].status;
    cell.failed = status == job_status::failed || status == job_status::crashed;
    if (status == job_status::rendered || status == job_status::skipped) cell.exr = batch_job_output(jobs[i]);
    cells.push_back(std::move(cell));
  }
  write_contact_sheet(path, cells);
}

// Writes the summary atomically, one job at a time (a million jobs' summary is never held whole);
// false (said on stderr) when it cannot. A job's message may quote bytes that are not UTF-8 (from a
// file's contents): they become U+FFFD instead of losing the summary.
bool write_summary(const std::string& path, const std::vector<batch_job>& jobs,
                   const std::vector<job_result>& results, int exit_code, double seconds,
                   const std::string& error) {
  std::map<std::string, int> counts{{"rendered", 0}, {"skipped", 0},     {"failed", 0},
                                    {"crashed", 0},  {"interrupted", 0}, {"not_started", 0}};
  for (const job_result& r : results) ++counts[status_name(r.status)];
  nlohmann::json totals = {{"jobs", jobs.size()}, {"seconds", seconds}};
  for (const auto& [name, count] : counts) totals[name] = count;
  const nlohmann::json summary = {{"version", 1},
                                  {"exit_code", exit_code},
                                  {"error", error.empty() ? nlohmann::json(nullptr) : nlohmann::json(error)},
                                  {"totals", totals}};
  try {
    write_json_list_atomically(path, summary, "jobs", jobs.size(),
                               [&](size_t i) { return summary_entry(jobs[i], results[i]); });
    return true;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "kiln: %s\n", message_of(e).c_str());
    return false;
  }
}

}  // namespace

void write_stopped_batch_summary(const std::string& path, const std::vector<batch_job>& jobs, int exit_code,
                                 const std::string& error, double seconds) {
  write_summary(path, jobs, std::vector<job_result>(jobs.size()), exit_code, seconds, error);
}

int run_batch_jobs(const std::vector<batch_job>& jobs, bool resume, const std::string& summary,
                   const std::string& contact_sheet, bool quiet) {
  const auto batch_start = std::chrono::steady_clock::now();
  std::vector<job_result> results(jobs.size());
  size_t done = 0, rendered = 0, failed = 0;
  double render_seconds = 0.0;
  bool interrupted = false;
  for (size_t i = 0; i < jobs.size() && !interrupted; ++i) {
    if (interrupt_requested()) break;  // a signal between jobs: the rest are not started
    const std::string label =
        "[" + std::to_string(i + 1) + "/" + std::to_string(jobs.size()) + "] " + jobs[i].name;
    try {
      results[i] = run_job(jobs[i], resume, label, quiet);
    } catch (const std::exception& e) {  // out of memory, or a failure outside the job's process
      results[i] = job_result{};
      results[i].status = job_status::failed;
      results[i].error = message_of(e);
    }
    const job_result& r = results[i];
    if (r.status == job_status::not_started) break;  // a signal just before its start
    interrupted = r.status == job_status::interrupted;
    ++done;
    if (r.status == job_status::rendered) {
      ++rendered;
      render_seconds += r.seconds;
    }
    if (r.status == job_status::failed || r.status == job_status::crashed) ++failed;
    if (quiet) continue;
    std::fprintf(stderr, "kiln batch: [%zu/%zu] %s %s %.2f s%s%s%s%s%s\n", i + 1, jobs.size(),
                 jobs[i].name.c_str(), status_name(r.status), r.seconds, r.error.empty() ? "" : ": ",
                 r.error.c_str(), r.resume.empty() ? "" : " (not resumed: ", r.resume.c_str(),
                 r.resume.empty() ? "" : ")");
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
  int exit_code = interrupted ? 128 + (interrupt_signal() ? interrupt_signal() : SIGINT) : failed ? 1 : 0;
  // A stopped batch makes no sheet: --resume finishes the jobs, and its sheet shows them all.
  if (!contact_sheet.empty() && !interrupted) {
    try {
      write_batch_contact_sheet(contact_sheet, jobs, results);
      if (!quiet) std::fprintf(stderr, "kiln batch: contact sheet -> %s\n", contact_sheet.c_str());
    } catch (const std::exception& e) {
      std::fprintf(stderr, "kiln: %s\n", message_of(e).c_str());
      if (!exit_code) exit_code = 1;
    }
  }
  if (!summary.empty() && !write_summary(summary, jobs, results, exit_code, seconds_since(batch_start), ""))
    return exit_code ? exit_code : 1;
  return exit_code;
}

}  // namespace kiln
