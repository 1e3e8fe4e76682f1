// The run loop of `kiln batch`: renders resolved jobs one after another, skips up-to-date
// outputs when resuming, keeps going past failures, stops at a signal, and reports progress and
// a JSON summary. App layer only.
#pragma once

#include <string>
#include <vector>

#include "app/batch_command.h"
#include "job/render_fingerprint.h"

namespace kiln {

// What happened to a job; crashed when a signal killed its process (it counts as failed);
// not_started when the batch stopped before it.
enum class job_status { rendered, skipped, failed, crashed, interrupted, not_started };

// True when output exists, every pixel reads back, its kiln/input_hash and kiln/settings_hash
// equal the fingerprint's, and, when the job asks for a preview, that preview is complete at the
// EXR's size: every output a job asks for must be there.
bool output_up_to_date(const std::string& output, const render_fingerprint& fingerprint,
                       const std::string& preview);

// Runs the jobs; writes the contact sheet (when contact_sheet is not empty) unless a signal stopped
// the batch, and the summary (when summary is not empty) whatever happens. Returns the exit code: 0
// all rendered or skipped, 1 any failed or crashed (or the sheet could not be written), 128 + signal
// when interrupted.
int run_batch_jobs(const std::vector<batch_job>& jobs, bool resume, const std::string& summary,
                   const std::string& contact_sheet, bool quiet);

}  // namespace kiln
