// kiln's command line: parses arguments, runs a subcommand, and maps every failure to one line
// on stderr and an exit code (0 success, 2 usage or bad input, 1 render or I/O failure,
// 3 when `kiln compare` finds the backends disagree, 124 when a render ran past --time-limit,
// 128 + n when signal n stopped a render;
// `kiln batch` exits 1 when any job failed).
#include <sys/prctl.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "app/batch_command.h"
#include "app/bench_command.h"
#include "app/cli_checks.h"
#include "app/cli_suggest.h"
#include "app/compare_command.h"
#include "app/exit_status.h"
#include "app/help_command.h"
#include "app/info_command.h"
#include "app/interrupt.h"
#include "app/render_command.h"
#include "app/stitch_command.h"
#include "core/error.h"

namespace {

constexpr int exit_success = 0;
constexpr int exit_bad_input = 2;

// A job of kiln batch: it stops (SIGTERM, handled like any) when the batch dies, so a killed
// batch leaves no render running on its own. KILN_TEST_ABORT_ASSET (test only, see
// tests/batch_cli_test.cpp) makes the job whose asset has that file name call abort(), a real
// crash for the batch to survive.
void start_batch_job(const kiln::render_options& job) {
  ::prctl(PR_SET_PDEATHSIG, SIGTERM);
  const char* abort_asset = std::getenv("KILN_TEST_ABORT_ASSET");
  if (abort_asset && std::filesystem::path(job.input).filename() == abort_asset) std::abort();
}

std::string join_arguments(int argc, char** argv) {
  std::string line;
  for (int i = 0; i < argc; ++i) {
    if (i) line += ' ';
    line += argv[i];
  }
  return line;
}

}  // namespace

int main(int argc, char** argv) {
  kiln::install_interrupt_handlers();  // first, so a signal never finds the default action
  CLI::App app{"kiln: renders glTF 2.0 assets to HDR OpenEXR with Embree and Whitted shading"};
  app.set_version_flag("--version", std::string("kiln ") + KILN_VERSION);
  app.require_subcommand(1);

  kiln::render_options render;
  render.command_line = join_arguments(argc, argv);
  CLI::App* render_command = app.add_subcommand("render", "Render a glTF asset to an OpenEXR image");
  kiln::add_render_options(*render_command, render);

  kiln::compare_options compare;
  compare.view.command_line = render.command_line;
  CLI::App* compare_command =
      app.add_subcommand("compare", "Trace one view with two backends and report where their answers differ");
  kiln::add_compare_options(*compare_command, compare);

  kiln::bench_options bench;
  bench.view.command_line = render.command_line;
  bench.view.quiet = false;
  CLI::App* bench_command = app.add_subcommand(
      "bench", "Time one view and replay its rays through a bare Embree loop (JSON and CSV reports)");
  kiln::add_bench_options(*bench_command, bench);

  kiln::stitch_options stitch;
  CLI::App* stitch_command = app.add_subcommand(
      "stitch", "Join region EXRs (e.g. the bands of render --band I/N) into one full-frame EXR");
  kiln::add_stitch_options(*stitch_command, stitch);

  kiln::batch_options batch;
  batch.defaults.command_line = render.command_line;
  CLI::App* batch_command = app.add_subcommand(
      "batch", "Render many assets (arguments, glob patterns or a manifest) with resume and a JSON summary");
  kiln::add_batch_options(*batch_command, batch);

  kiln::info_options info;
  CLI::App* info_command = app.add_subcommand(
      "info",
      "List an asset's cameras, animations, variants, lights, nodes and extensions, and estimate its render");
  kiln::add_info_options(*info_command, info);

  // Hidden: `kiln help --man`, `--markdown` and the completion scripts, written from the parsers.
  kiln::help_format help = kiln::help_format::usage;
  CLI::App* help_command = app.add_subcommand("help", "Print this help, the man page or a completion script");
  help_command->group("");
  kiln::add_help_options(*help_command, help);

  kiln::require_integer_text(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {
    return app.exit(e);  // --help, --version
  } catch (const CLI::ParseError& e) {
    // A mistyped command or option is named with the closest known one, whatever CLI11 tripped over
    // first (a missing -o, or "arguments were not expected").
    const std::vector<std::string> arguments(argv + 1, argv + argc);
    std::optional<std::string> better = kiln::unknown_command_message(app, arguments);
    // No message about the command: arguments[0] is an option or names a subcommand.
    if (!better && !arguments.empty() && !arguments[0].empty() && arguments[0][0] != '-')
      better = kiln::unknown_option_message(*app.get_subcommand(arguments[0]),
                                            {arguments.begin() + 1, arguments.end()});
    std::string message = better.value_or(e.what());
    std::cerr << "kiln: " << message << " (run 'kiln --help' or 'kiln render --help')\n";
    return exit_bad_input;
  }

  try {
    if (render_command->parsed()) {
      if (render.batch_job) start_batch_job(render);
      kiln::run_render(render);
    }
    if (compare_command->parsed()) return kiln::run_compare(compare);  // 0, or 3 on disagreement
    if (bench_command->parsed()) kiln::run_bench_command(bench);
    if (stitch_command->parsed()) kiln::run_stitch(stitch);
    if (info_command->parsed()) kiln::run_info(info);
    if (help_command->parsed()) kiln::run_help(app, help);
    if (batch_command->parsed()) return kiln::run_batch(batch);  // 0, 1 when a job failed, 128 + signal
    return exit_success;
  } catch (const std::exception& e) {
    std::cerr << "kiln: " << kiln::message_of(e) << '\n';
    return kiln::exit_status_of(e);
  }
}
