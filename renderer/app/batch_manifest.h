// `kiln batch --manifest FILE`: reads a JSON or CSV list of render jobs into job descriptions
// whose options are still `kiln render` arguments, so the render's own parser validates them.
// App layer only: no rendering, no image formats.
#pragma once

#include <string>
#include <vector>

namespace kiln {

// One job as written, before any option is applied.
struct batch_job_spec {
  std::string asset;                   // absolute, or as given on the command line
  std::string output;                  // as written; empty: the default name
  std::string camera;                  // the job's camera field, for the default output name
  std::vector<std::string> arguments;  // `kiln render` options from the job's fields and overrides
  // "variants": KHR_materials_variants to render one job each (names or indices), or all_variants.
  std::vector<std::string> variants;
  bool all_variants = false;
  std::string where;  // "FILE: /jobs/3" or "FILE: line 4": where the job came from
};

struct batch_manifest {
  std::vector<std::string> default_arguments;  // the JSON manifest's "defaults", as render options
  std::vector<batch_job_spec> jobs;
};

// Reads FILE by its extension (.json or .csv). Relative asset paths resolve against FILE's folder.
// Throws kiln::error (input) naming FILE, the JSON pointer or CSV line, and the problem.
batch_manifest read_manifest(const std::string& path);

// Splits "--max-depth 4 --aovs 'beauty,Z'" into arguments as a POSIX shell would (quotes, no
// expansion).
std::vector<std::string> split_arguments(const std::string& text);

}  // namespace kiln
