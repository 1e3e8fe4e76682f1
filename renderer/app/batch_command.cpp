#include "app/batch_command.h"

#include <glob.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <tuple>
#include <unordered_map>

#include "app/batch_manifest.h"
#include "app/batch_run.h"
#include "app/cli_checks.h"
#include "app/cli_suggest.h"
#include "app/exit_status.h"
#include "app/interrupt.h"
#include "app/option_cli.h"
#include "app/output_lock.h"
#include "app/text_output.h"
#include "core/error.h"
#include "core/message_text.h"
#include "io/exr/exr_writer.h"
#include "io/exr/preview_codes.h"
#include "io/gltf/gltf_loader.h"
#include "job/asset_file.h"
#include "job/deep_output.h"
#include "job/frame_range.h"
#include "job/option_table.h"
#include "job/output_guard.h"
#include "job/plan_estimate.h"
#include "job/render_fingerprint.h"
#include "job/render_sequence.h"

namespace kiln {

namespace {

namespace fs = std::filesystem;

// Why text cannot be a job's asset, output or name, or "": every name a batch accepts must pass
// through JSON (the plan, the summary) and one shell-quoted line of a farm's task list.
std::string unprintable(const std::string& text) {
  for (size_t i = 0; i < text.size();) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    if (c < 0x20 || c == 0x7f) return "contains a control character";
    // UTF-8: a lead byte, then as many continuation bytes (10xxxxxx) as it announces.
    const size_t length = c < 0x80 ? 1 : (c >> 5) == 0x6 ? 2 : (c >> 4) == 0xe ? 3 : (c >> 3) == 0x1e ? 4 : 0;
    if (length == 0 || i + length > text.size()) return "is not valid UTF-8";
    for (size_t k = 1; k < length; ++k)
      if ((static_cast<unsigned char>(text[i + k]) >> 6) != 0x2) return "is not valid UTF-8";
    i += length;
  }
  return "";
}

bool is_pattern(const std::string& text) { return text.find_first_of("*?[") != std::string::npos; }

// glob(3) ourselves, so a quoted pattern works and the order is the same on every shell (sorted).
std::vector<std::string> expand_pattern(const std::string& pattern) {
  glob_t matches{};
  const int status = ::glob(pattern.c_str(), 0, nullptr, &matches);
  std::vector<std::string> files;
  if (status == 0)
    for (size_t i = 0; i < matches.gl_pathc; ++i) files.push_back(matches.gl_pathv[i]);
  ::globfree(&matches);
  if (files.empty()) throw input_error("", pattern, "the pattern matches no file");
  return files;
}

std::string absolute_path(const std::string& path) { return fs::absolute(path).lexically_normal().string(); }

// The default output name: the asset's stem, then _<camera> when the job names one, then a frame
// placeholder for a sequence's frames (Nuke's and Blender's ####).
std::string default_output(const batch_job_spec& spec, bool sequence) {
  std::string name = fs::path(spec.asset).stem().string();
  if (!spec.camera.empty()) name += "_" + spec.camera;
  return name + (sequence ? ".####.exr" : ".exr");
}

// Every job's EXR and preview, and the contact sheet, against every file any job reads (one job's
// output must not replace another's asset, buffer or environment map) and the rules of kiln
// render: .exr, no symlink.
void check_batch_outputs(const std::vector<batch_job>& jobs, const std::string& contact_sheet) {
  std::vector<input_file> files;
  // The files a job reads depend on these options alone; the frames of a sequence (up to a million)
  // share them, so the asset's JSON is read once per sequence, not once per frame.
  std::set<std::tuple<std::string, std::string, bool, uint64_t, uint64_t>> read_already;
  const batch_entry* last_entry = nullptr;
  for (const batch_job& job : jobs) {
    if (job.entry.get() == last_entry) continue;
    last_entry = job.entry.get();
    const render_options& o = job.entry->options;
    if (!read_already
             .emplace(o.input, o.environment, o.allow_outside_files, o.limits.max_json_bytes, o.max_memory)
             .second)
      continue;
    std::vector<input_file> read = render_input_files(batch_job_options(job), &interrupt_requested());
    files.insert(files.end(), read.begin(), read.end());
  }
  const input_index inputs = index_inputs(files);  // one stat per file, not per pair
  for (const batch_job& job : jobs) {
    try {
      const render_options o = batch_job_options(job);
      check_output_spares_inputs(o.output, "output", inputs);
      if (!o.preview.empty()) check_output_spares_inputs(o.preview, "--preview", inputs);
      check_not_symlink(o.output, "output");
      if (!o.preview.empty()) check_not_symlink(o.preview, "--preview");
      check_exr_output_name(o.output, "output", preview_hint::hide);
      if (o.deep) {
        check_output_spares_inputs(deep_output_path(o.output), "--deep", inputs);
        check_not_symlink(deep_output_path(o.output), "--deep");
      }
    } catch (const error& e) {
      throw input_error("", job.entry->where, e.what());
    }
  }
  if (contact_sheet.empty()) return;
  check_output_spares_inputs(contact_sheet, "--contact-sheet", inputs);
  check_not_symlink(contact_sheet, "--contact-sheet");
  const fs::path sheet = fs::absolute(contact_sheet).lexically_normal();
  for (const batch_job& job : jobs) {
    const render_options o = batch_job_options(job);
    for (const std::string& written : {o.output, o.preview})
      if (!written.empty() && fs::path(written).lexically_normal() == sheet)
        throw input_error("", "--contact-sheet",
                          "'" + contact_sheet + "' is also written by " + job.entry->where);
  }
}

// A job's plan-time estimate for the farm (job/plan_estimate.h); null when its asset cannot be
// rendered (a missing file fails its job alone, when it runs).
nlohmann::json estimate_json(const render_options& options) {
  render_options probe = options;
  probe.quiet = true;
  plan_estimate e;
  try {
    e = estimate_job(probe);
  } catch (const error&) {
    return nullptr;
  }
  return {{"seconds", e.load_seconds + e.render_seconds},
          {"load_seconds", e.load_seconds},
          {"render_seconds", e.render_seconds},
          {"threads", 1},
          {"peak_memory_bytes", e.peak_memory_bytes},
          {"probe", {e.probe_width, e.probe_height, e.probe_spp}}};
}

// Writes the plan one job at a time (a million frames' plan is never held whole); every job is
// checked before anything is written.
void write_plan(const std::string& path, const std::vector<batch_job>& jobs, bool estimates) {
  for (const batch_job& job : jobs) {
    const batch_entry& entry = *job.entry;
    if (!entry.error.empty()) throw input_error("", entry.where, entry.error);
    if (entry.options.crop || entry.options.band_count > 0)
      throw input_error("", entry.where, "a plan leaves --crop and --band to whoever runs it; drop them");
  }
  write_json_list_atomically(path, {{"version", 1}}, "jobs", jobs.size(), [&](size_t i) {
    const batch_job& job = jobs[i];
    const render_options options = batch_job_options(job);
    std::vector<std::string> args = canonical_render_arguments(options, region_arguments::omit);
    if (options.threads) args.insert(args.end(), {"--threads", std::to_string(options.threads)});
    nlohmann::json entry = {
        {"name", job.name}, {"asset", options.input}, {"output", options.output}, {"render_args", args}};
    if (nlohmann::json estimate = estimates ? estimate_json(options) : nullptr; !estimate.is_null())
      entry["estimate"] = estimate;
    return entry;
  });
}

}  // namespace

void add_batch_options(CLI::App& app, batch_options& o) {
  app.add_option(
      "assets", o.assets,
      "glTF assets or glob patterns (quoted patterns such as 'assets/*/*.gltf' are expanded by kiln)");
  add_table_options(app, o.defaults, {option_scope::view, option_scope::image, option_scope::progress});
  app.add_option("--manifest", o.manifest, "Jobs from a .json or .csv manifest (docs/batch.md)")
      ->check(CLI::ExistingFile);
  app.add_option("--out-dir", o.out_dir, "Folder for the outputs (created when missing)")->required();
  app.add_flag(
      "--resume", o.resume,
      "Skip jobs whose output exists, reads back complete and records the same input and settings hashes");
  app.add_flag("--wait-for-lock", o.wait_for_lock,
               "When another batch holds --out-dir, wait for it instead of refusing (exit 2)");
  app.add_option("--summary", o.summary,
                 "Write a JSON summary of every job (also after a failure or a signal)");
  app.add_option("--plan-only", o.plan, "Write the resolved job plan as JSON and render nothing");
  app.add_option(
      "--contact-sheet", o.contact_sheet,
      "After the jobs, write FILE.png or FILE.jpg: every job's beauty in a grid, its name under it, "
      "failed jobs marked");
  app.add_flag_callback(
      "--no-estimates", [&o] { o.plan_estimates = false; },
      "With --plan-only: leave out the per-job estimates of time and memory (each costs a load and a small "
      "probe render of the asset)");
}

void apply_render_arguments(render_options& options, const std::vector<std::string>& arguments) {
  CLI::App parser{"kiln render options"};
  parser.set_help_flag();  // no --help inside a manifest
  // Later arguments refine earlier ones: manifest defaults, then the job's fields, then overrides.
  parser.option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  add_view_settings(parser, options);
  add_image_options(parser, options);
  require_integer_text(parser);
  std::vector<std::string> reversed(arguments.rbegin(), arguments.rend());  // CLI11 takes them last first
  try {
    parser.parse(reversed);
  } catch (const CLI::ParseError& e) {
    // A mistyped manifest key is named with the closest render option, as on the command line.
    if (std::optional<std::string> better = unknown_option_message(parser, arguments))
      throw CLI::ParseError(*better, e.get_exit_code());
    throw;
  }
}

// A variant's name as part of a file name: letters, digits, '.', '-' and '_' kept, the rest '_'.
std::string file_safe(const std::string& name) {
  std::string out = name.empty() ? "variant" : name;
  for (char& c : out)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '-' && c != '_') c = '_';
  return out;
}

// The output of one variant: {variant} in the name replaced, else _<variant> before the extension.
std::string variant_output(const std::string& output, const std::string& variant) {
  const std::string safe = file_safe(variant);
  const size_t token = output.rfind("{variant}");
  if (token != std::string::npos) return output.substr(0, token) + safe + output.substr(token + 9);
  fs::path path(output);
  return (path.parent_path() / (path.stem().string() + "_" + safe + path.extension().string())).string();
}

// The entries of a manifest job's "variants": one per KHR_materials_variants variant, each with
// --variant and its own output; the job itself when it names none. "all" reads the asset's list;
// an asset that cannot be read fails its job alone, as it would when rendering.
std::vector<batch_entry> variant_entries(batch_entry job, const batch_job_spec& spec) {
  std::vector<std::string> variants = spec.variants;
  if (spec.all_variants && job.error.empty()) {
    try {
      variants = gltf_material_variants(job.options.input);
      if (variants.empty())
        job.error = "\"variants\": \"all\": the asset has no KHR_materials_variants variants";
    } catch (const error& e) {
      job.error = e.what();
    }
  }
  if (variants.empty() || !job.error.empty()) return {std::move(job)};
  std::vector<batch_entry> out;
  for (const std::string& variant : variants) {
    batch_entry one = job;
    one.options.variant = variant;
    one.options.output = variant_output(job.options.output, variant);
    out.push_back(std::move(one));
  }
  return out;
}

// The files job writes: its EXR and, with --deep, the deep EXR.
std::vector<std::string> written_files(const batch_job& job) {
  std::vector<std::string> files = {batch_job_output(job)};
  if (job.entry->options.deep) files.push_back(deep_output_path(files.front()));
  return files;
}

// The files the batch has planned so far and the names it has given, so that no two jobs write
// one file and every job's name is unique. Kept by hash with the job that holds the text: a
// million frames' paths would take more than their jobs. Texts whose hashes meet are compared.
struct planned_outputs {
  std::unordered_multimap<size_t, size_t> writers;                // a file's hash -> the job that writes it
  std::unordered_multimap<size_t, std::pair<size_t, int>> names;  // a name's hash -> its first job, its jobs
};

// Adds a job whose entry is complete: a unique output and name.
void add_planned_job(batch_job job, const fs::path& out_dir, std::vector<batch_job>& jobs,
                     planned_outputs& planned) {
  const batch_entry& entry = *job.entry;
  // The deep file (--deep) is written too: no other job may write it, as its EXR or its own deep file.
  const std::vector<std::string> written = written_files(job);
  std::vector<size_t> hashes;
  for (const std::string& file : written) {
    hashes.push_back(std::hash<std::string>{}(file));
    auto [begin, end] = planned.writers.equal_range(hashes.back());
    for (auto it = begin; it != end; ++it) {
      const std::vector<std::string> other = written_files(jobs[it->second]);
      if (std::find(other.begin(), other.end(), file) != other.end())
        throw input_error("", entry.where,
                          "writes " + file + ", as does " + jobs[it->second].entry->where +
                              " (give one of them another output)");
    }
  }
  for (size_t hash : hashes) planned.writers.emplace(hash, jobs.size());
  const std::string& output = written.front();
  // The name is the output under --out-dir; one outside it (an absolute output) goes by its stem.
  const fs::path output_path(output);
  fs::path relative = output_path.lexically_relative(out_dir);
  job.name = (relative.empty() || *relative.begin() == "..") ? output_path.stem().string()
                                                             : relative.replace_extension().string();
  const size_t name_hash = std::hash<std::string>{}(job.name);
  auto [begin, end] = planned.names.equal_range(name_hash);
  const auto same =
      std::find_if(begin, end, [&](const auto& seen) { return jobs[seen.second.first].name == job.name; });
  if (same == end)
    planned.names.emplace(name_hash, std::make_pair(jobs.size(), 1));
  else
    job.name += "-" + std::to_string(++same->second.second);
  for (const std::string* text : {&entry.options.input, &output})
    if (const std::string why = unprintable(*text); !why.empty())
      throw input_error(
          "", entry.where,
          "the path " + nlohmann::json(*text).dump(-1, ' ', true, nlohmann::json::error_handler_t::replace) +
              " " + why);
  jobs.push_back(std::move(job));
}

// True when path lies below folder (both absolute and normal).
bool lies_below(const fs::path& path, const fs::path& folder) {
  const fs::path relative = path.lexically_relative(folder);
  return !relative.empty() && relative != "." && *relative.begin() != "..";
}

// A manifest's output stays inside --out-dir, the folder the batch locks and owns: "../x.exr", an
// absolute path elsewhere, or a subfolder that is a symbolic link out of it would let a manifest
// from elsewhere write any file the batch's user can.
void check_inside_out_dir(const fs::path& output, const fs::path& out_dir, const batch_job_spec& spec) {
  std::error_code ec, dir_ec;
  const fs::path resolved = fs::weakly_canonical(output, ec),
                 resolved_dir = fs::weakly_canonical(out_dir, dir_ec);
  const bool followed = ec || dir_ec || lies_below(resolved, resolved_dir);
  if (lies_below(output, out_dir) && followed) return;
  const fs::path shown_at = lies_below(output, out_dir) ? resolved : output;
  throw input_error("", spec.where,
                    "output " + quoted(spec.output) + " resolves to " + quoted(shown_at.string()) +
                        ", outside --out-dir " + quoted(out_dir.string()) +
                        " (outputs stay inside the folder the batch locks)");
}

render_options batch_job_options(const batch_job& job) {
  return job.frame ? frame_options(job.entry->options, *job.frame) : job.entry->options;
}

std::string batch_job_output(const batch_job& job) {
  return job.frame ? frame_path(job.entry->options.output, *job.frame) : job.entry->options.output;
}

std::vector<batch_job> plan_batch(const batch_options& options) {
  std::vector<batch_job_spec> specs;
  for (const std::string& argument : options.assets) {
    for (const std::string& file : is_pattern(argument) ? expand_pattern(argument) : std::vector{argument}) {
      batch_job_spec spec;
      spec.asset = absolute_path(file);
      spec.where = file;
      specs.push_back(spec);
    }
  }
  std::vector<std::string> manifest_defaults;
  if (!options.manifest.empty()) {
    batch_manifest manifest = read_manifest(options.manifest);
    manifest_defaults = manifest.default_arguments;
    specs.insert(specs.end(), manifest.jobs.begin(), manifest.jobs.end());
  }
  if (specs.empty()) throw input_error("", "kiln batch", "no jobs: give assets, glob patterns or --manifest");
  // A folder (or FIFO, device) is bad input for the whole batch; a missing file fails its job alone.
  for (const batch_job_spec& spec : specs) check_asset_file(spec.asset, spec.where);

  const fs::path out_dir = fs::absolute(options.out_dir).lexically_normal();
  std::vector<batch_job> jobs;
  planned_outputs planned;
  for (const batch_job_spec& spec : specs) {
    batch_entry job;
    job.where = spec.where;
    job.options = options.defaults;
    job.options.input = spec.asset;
    job.options.summary_line = false;
    std::vector<std::string> arguments = manifest_defaults;
    arguments.insert(arguments.end(), spec.arguments.begin(), spec.arguments.end());
    try {
      apply_render_arguments(job.options, arguments);
    } catch (const CLI::ParseError& e) {
      job.error = std::string("bad render options: ") + e.what();
    }
    const bool sequence = renders_sequence(job.options) && job.error.empty();
    const fs::path output = out_dir / (spec.output.empty() ? default_output(spec, sequence) : spec.output);
    if (!spec.output.empty()) check_inside_out_dir(output.lexically_normal(), out_dir, spec);
    job.options.output = output.lexically_normal().string();
    for (batch_entry& one : variant_entries(std::move(job), spec)) {
      // --preview in a batch names the format only: each job's preview sits beside its EXR.
      if (!one.options.preview.empty())
        one.options.preview = fs::path(one.options.output)
                                  .replace_extension(fs::path(one.options.preview).extension())
                                  .string();
      auto entry = std::make_shared<const batch_entry>(std::move(one));
      if (!sequence) {
        add_planned_job({"", entry, std::nullopt}, out_dir, jobs, planned);
        continue;
      }
      // A sequence (--frames, --turntable) is one job per frame, each with its own output, resume
      // state and farm task.
      std::vector<long long> frames;
      try {
        frames = sequence_frames(entry->options);
      } catch (const error& e) {
        throw input_error("", spec.where, e.what());
      }
      if (frames.size() > 1 && !has_frame_placeholder(entry->options.output))
        throw input_error("", spec.where,
                          "output " + entry->options.output +
                              " has no frame placeholder for its frames (name it like shot.####.exr)");
      // Room for the frames at once (a million jobs grown by doubling would hold twice that).
      if (jobs.capacity() - jobs.size() < frames.size())
        jobs.reserve(std::max(jobs.size() + frames.size(), 2 * jobs.capacity()));
      for (long long frame : frames) add_planned_job({"", entry, frame}, out_dir, jobs, planned);
    }
  }
  check_batch_outputs(jobs, options.contact_sheet);
  return jobs;
}

// What job_option_warnings says of the jobs, each line once (the batch's options reach every job).
void print_option_warnings(const std::vector<batch_job>& jobs) {
  std::set<std::string> given;
  const batch_entry* last_entry = nullptr;
  for (const batch_job& job : jobs) {
    if (job.entry.get() == last_entry) continue;  // a sequence's frames warn as their first does
    last_entry = job.entry.get();
    for (const std::string& line : job_option_warnings(batch_job_options(job)))
      if (given.insert(line).second) std::fprintf(stderr, "kiln: %s\n", line.c_str());
  }
}

// Creates --out-dir (and its parents) when missing.
void create_out_dir(const std::string& out_dir) {
  std::error_code ec;
  fs::create_directories(out_dir, ec);
  if (!fs::is_directory(out_dir)) throw io_error(out_dir, "cannot create the output folder");
}

int run_batch(const batch_options& options) {
  if (!options.contact_sheet.empty()) {
    if (!options.plan.empty())
      throw input_error("", "--contact-sheet",
                        "a plan renders nothing; make the sheet with the batch that renders");
    if (preview_format(options.contact_sheet).empty())
      throw input_error(
          "", "--contact-sheet",
          "a contact sheet must end in .png, .jpg or .jpeg, got '" + options.contact_sheet + "'");
  }
  if (!options.plan.empty()) {
    check_output_writable(options.plan);
    write_plan(options.plan, plan_batch(options), options.plan_estimates);
    return 0;
  }
  if (!options.summary.empty()) {
    // A summary inside --out-dir goes in the folder the batch creates anyway: create it first.
    if (lies_below(fs::absolute(options.summary).lexically_normal(),
                   fs::absolute(options.out_dir).lexically_normal()))
      create_out_dir(options.out_dir);
    check_output_writable(options.summary);
  }
  // From here the summary is written whatever stops the batch: a refused plan, an unusable folder,
  // a job in another batch's folder, out of memory, a signal. Only when another batch holds the
  // folder is it left alone: the summary named may be that batch's.
  const auto start = std::chrono::steady_clock::now();
  std::vector<batch_job> jobs;
  bool locking = false;
  try {
    jobs = plan_batch(options);
    print_option_warnings(jobs);
    create_out_dir(options.out_dir);  // before the contact sheet's check: it may lie inside
    if (!options.contact_sheet.empty()) check_output_writable(options.contact_sheet);
    const std::string out_dir = absolute_path(options.out_dir);
    locking = true;
    const output_folder_lock lock(out_dir, options.wait_for_lock);
    locking = false;
    // Another running batch's folder inside this one is its own subtree: no job may write there.
    for (const batch_job& job : jobs) {
      try {
        check_not_in_locked_folder(batch_job_output(job), out_dir);
      } catch (const error& e) {
        throw input_error("", job.entry->where, e.what());
      }
    }
    return run_batch_jobs(jobs, options.resume, options.summary, options.contact_sheet,
                          options.defaults.quiet);
  } catch (const std::exception& e) {
    if (!options.summary.empty() && !locking)
      write_stopped_batch_summary(
          options.summary, jobs, exit_status_of(e), message_of(e),
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    throw;
  }
}

}  // namespace kiln
