// kiln as a C++ library: loads a glTF asset, renders it with the render job (the call `kiln render`
// makes) and writes the EXR. Built against the installed CMake package (find_package(kiln)):
//   render_gltf ASSET OUT.exr [OPTION=VALUE ...]   e.g. spp=4 width=320 camera=1
#include <kiln/core/error.h>
#include <kiln/job/option_table.h>
#include <kiln/job/render_job.h>

#include <cstdio>
#include <string>

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: render_gltf ASSET OUT.exr [OPTION=VALUE ...]\n");
    return 2;
  }
  kiln::render_job job;
  job.options.input = argv[1];
  job.options.output = argv[2];
  job.warn = [](const std::string& line) { std::fprintf(stderr, "render_gltf: %s\n", line.c_str()); };
  try {
    // Any option of `kiln render` by name, checked as the CLI checks it; a bare name sets a flag.
    for (int i = 3; i < argc; ++i) {
      const std::string arg = argv[i];
      const size_t equals = arg.find('=');
      kiln::set_render_option(job.options, arg.substr(0, equals),
                              equals == std::string::npos ? "true" : arg.substr(equals + 1));
    }
    const kiln::render_job_result result = kiln::run_job(job);
    kiln::write_job_outputs(result, job.options);
    std::printf("render_gltf: %dx%d in %.3f s -> %s\n", result.width, result.height, result.stats.seconds,
                argv[2]);
  } catch (const kiln::error& e) {
    // One line naming the file, the location (a JSON pointer or an option) and the reason.
    std::fprintf(stderr, "%s\n", e.what());
    return e.kind() == kiln::error_kind::input ? 2 : 1;
  }
  return 0;
}
