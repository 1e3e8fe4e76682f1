// The render option table: the one place an option of `kiln render` is declared. Each entry
// names the option, parses and checks its text into render_options, and gives back its value; the
// command-line parser (app/option_cli.h), batch manifests, the Python module, the canonical
// arguments behind the settings hash, the EXR metadata, the man page, the shell completions and
// docs/options.md all come from it. Adding an option is one entry here, in a group (and a row in
// the docs' option tables that explains it, which a test checks).
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "io/exr/exr_value.h"
#include "job/render_options.h"

namespace kiln {

// Which commands declare an option.
enum class option_scope {
  view,      // everything that traces a view: render, batch, compare, bench
  image,     // what the EXR holds and how: render and batch
  progress,  // progress lines: render and batch
};

// What an option changes. pixels and region options reach the settings hash (a changed value
// makes a stored EXR stale); region options are left out of the frame's hash, which every band
// or crop of one frame shares.
enum class option_effect { pixels, region, none };

// The task an option serves: --help, the man page and the docs list the options group by group, in
// this order (what to write first, the loader's limits last). unassigned is no group: the table's
// tests refuse an entry left in it.
enum class option_group {
  unassigned,
  output,
  camera,
  sampling,
  lighting,
  aovs,
  animation,
  layers,
  colour,
  performance,
  progress,
  limits,
};

// Every group but unassigned, in order.
const std::vector<option_group>& option_groups();

// A group's heading: "Output", "Camera and scene", ...
const char* option_group_title(option_group group);

// The kind of value, for help texts (INT, UINT, FLOAT, TEXT) and the Python module's conversion.
enum class option_type { integer, unsigned_integer, number, text, flag };

// How a recorded value is stored in the EXR header: by the option's type (integers as int,
// numbers as float, flags as "on"/"off", the rest as text), or as a double (a time that must read
// back exactly), a v2f or a v3f (a text of two or three numbers).
enum class record_type { by_type, float64, float2, float3 };

struct option_spec {
  std::string name;        // "spp": --spp on the command line, "spp" in a manifest, spp= in Python
  std::string short_name;  // "q" for -q; empty: none
  std::string alias;       // a deprecated name still accepted (with a warning); empty: none
  option_type type = option_type::text;
  option_scope scope = option_scope::view;
  option_effect effect = option_effect::pixels;
  option_group group = option_group::unassigned;
  std::string help;
  std::vector<std::string> choices;  // the values a choice takes; empty: any text of the type
  bool names_file = false;           // the value is a file's path (shell completion offers files)
  // Parses text (a flag's: "true" or "false") into options; throws kiln::error (input) whose
  // location is "--NAME" and whose reason says what is expected.
  std::function<void(render_options&, const std::string&)> set;
  // The value in canonical text (reads back through set to the same options); nullopt while an
  // optional value is not given. A flag's is "true" or "false".
  std::function<std::optional<std::string>(const render_options&)> get;
  std::string recorded_as;  // the EXR attribute holding the value ("kiln/..."); empty: not recorded
  record_type recorded_type = record_type::by_type;
  std::string example;  // a valid value other than the default, for the table's own tests
};

// Every render option, in the order of the canonical arguments (--help shows them group by group,
// in this order inside a group).
const std::vector<option_spec>& render_option_table();

// The entry named name (with or without the leading dashes, or its alias); nullptr if none.
const option_spec* find_render_option(const std::string& name);

// Sets one option from text by name; throws kiln::error (input) for an unknown name or bad text.
void set_render_option(render_options& options, const std::string& name, const std::string& text);

// Whether the canonical arguments include the region options (--crop, --band).
enum class region_arguments { include, omit };

// Every `kiln render` argument that reproduces options except the asset, -o, and the options
// without effect (threads, -q, the preview): each option with its value, flags only when set,
// optional values only when given. Floats are printed with enough digits to read back exactly.
std::vector<std::string> canonical_render_arguments(const render_options& options, region_arguments region);

// The EXR attributes of every recorded option given a value, stored as its recorded_type says:
// {"kiln/samples_per_pixel", 4}, {"kiln/shutter", vec2(-0.25, 0.25)}, {"kiln/deep", "on"}.
std::vector<std::pair<std::string, exr_value>> recorded_option_attributes(const render_options& options);

}  // namespace kiln
