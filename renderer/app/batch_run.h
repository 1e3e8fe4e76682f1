// The run loop of `kiln batch`: renders resolved jobs one after another, skips up-to-date
// outputs when resuming, keeps going past failures, stops at a signal, and reports progress and
// a JSON summary. App layer only.
#pragma once

#include <string>
#include <vector>

#include "app/batch_command.h"
#include "job/render_fingerprint.h"

namespace kiln {

class memory_budget;

// What happened to a job; crashed when a signal killed its process (it counts as failed);
// not_started when the batch stopped before it.
enum class job_status { rendered, skipped, failed, crashed, interrupted, not_started };

// Why --resume may not keep options' outputs as done, as "FILE: problem", or "" when it may: every
// file the job writes (the EXR, with --deep the deep EXR, with --preview the preview) exists, reads
// to its end and gives the content checksum it recorded when written (io/exr/exr_verify.h,
// io/exr/preview_record.h); the EXRs' kiln/input_hash and kiln/settings_hash equal the
// fingerprint's; the deep file's windows are the EXR's and the preview has the EXR's size. Reads
// a band of rows at a time, charged to budget.
std::string resume_problem(const render_options& options, const render_fingerprint& fingerprint,
                           memory_budget* budget);

// Runs the jobs; writes the contact sheet (when contact_sheet is not empty) unless a signal stopped
// the batch, and the summary (when summary is not empty) whatever happens. Returns the exit code: 0
// all rendered or skipped, 1 any failed or crashed (or the sheet could not be written), 128 + signal
// when interrupted.
// The summary of a batch that stopped before its jobs ran (its plan refused, its folder unusable,
// out of memory): every job in jobs (possibly none) not_started, error and exit_code at the top.
// Never throws; a summary that cannot be written is said on stderr.
void write_stopped_batch_summary(const std::string& path, const std::vector<batch_job>& jobs, int exit_code,
                                 const std::string& error, double seconds);

int run_batch_jobs(const std::vector<batch_job>& jobs, bool resume, const std::string& summary,
                   const std::string& contact_sheet, bool quiet);

}  // namespace kiln
