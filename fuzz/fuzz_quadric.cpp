// libFuzzer target for the KILN_quadric extension. The input's first line becomes the value of
// /extensions/KILN_quadric (the shared definitions) and the rest the value of
// /nodes/0/extensions/KILN_quadric (a placement), spliced into a fixed glTF with one material;
// the loader then parses, validates and bounds them. Every definition that loads is also hit by
// a fan of rays from outside its bounds: a reported hit must have a finite t inside the ray's
// interval and a finite unit normal. The only acceptable outcomes are a Scene or a kiln::error.
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "geometry/quadric.h"
#include "io/gltf/gltf_loader.h"

namespace {

namespace fs = std::filesystem;

std::string asset_path;

// Splits the input at its first newline; a missing placement places definition 0.
void split_input(const std::string& text, std::string& definitions, std::string& placement) {
  const size_t newline = text.find('\n');
  definitions = text.substr(0, newline);
  placement = newline == std::string::npos ? "" : text.substr(newline + 1);
  if (placement.find_first_not_of(" \t\r\n") == std::string::npos) placement = "{\"primitive\":0}";
}

std::string make_asset(const std::string& definitions, const std::string& placement) {
  return "{\"asset\":{\"version\":\"2.0\"},\"extensionsUsed\":[\"KILN_quadric\"],"
         "\"extensionsRequired\":[\"KILN_quadric\"],\"materials\":[{\"name\":\"m\"}],"
         "\"extensions\":{\"KILN_quadric\":" +
         definitions + "},\"nodes\":[{\"extensions\":{\"KILN_quadric\":" + placement +
         "}}],\"scenes\":[{\"nodes\":[0]}],\"scene\":0}";
}

void check(bool ok, const char* what) {
  if (ok) return;
  std::fprintf(stderr, "fuzz_quadric: %s\n", what);
  std::abort();
}

// Rays from a box around the bounds toward points inside it: hits must be well formed.
void trace_fan(const kiln::quadric& q) {
  const kiln::dvec3 lo = q.bounds.lower, hi = q.bounds.upper;
  if (!(std::isfinite(lo.x) && std::isfinite(lo.y) && std::isfinite(lo.z) && std::isfinite(hi.x) &&
        std::isfinite(hi.y) && std::isfinite(hi.z)))
    return;  // unbounded boxes are refused by the loader; nothing here to aim at
  const kiln::dvec3 centre = 0.5 * (lo + hi), half = 0.5 * (hi - lo) + kiln::dvec3(1e-3);
  const kiln::dvec3 origins[] = {centre + kiln::dvec3(3.0 * half.x, 0.1 * half.y, 0.2 * half.z),
                                 centre - kiln::dvec3(0.3 * half.x, 3.0 * half.y, 0.1 * half.z),
                                 centre + kiln::dvec3(0.2 * half.x, -0.1 * half.y, 3.0 * half.z),
                                 centre + 2.0 * half};
  for (const kiln::dvec3& o : origins)
    for (int k = 0; k < 5; ++k) {
      const kiln::dvec3 target =
          centre + half * kiln::dvec3(0.37 * (k - 2), 0.21 * (k % 3 - 1), 0.13 * (2 - k));
      const kiln::dvec3 d = target - o;
      const double tmax = 1e30;
      const auto hit = kiln::intersect_quadric(q, o, d, 0.0, tmax);
      if (!hit) continue;
      check(std::isfinite(hit->t) && hit->t > 0.0 && hit->t < tmax, "hit t outside the ray's interval");
      const kiln::quadric_surface s = kiln::quadric_surface_at(q, hit->part, o + hit->t * d);
      check(std::isfinite(s.normal.x) && std::isfinite(s.normal.y) && std::isfinite(s.normal.z),
            "non-finite surface normal");
    }
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  const fs::path folder = fs::temp_directory_path() / ("kiln_fuzz_quadric_" + std::to_string(::getpid()));
  fs::create_directories(folder);
  asset_path = (folder / "asset.gltf").string();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::string definitions, placement;
  split_input(std::string(reinterpret_cast<const char*>(data), size), definitions, placement);
  // Text that is not JSON never reaches the extension reader; keep it out of the corpus.
  if (!nlohmann::json::accept(definitions) || !nlohmann::json::accept(placement)) return -1;
  {
    std::ofstream out(asset_path, std::ios::binary | std::ios::trunc);
    out << make_asset(definitions, placement);
  }
  try {
    const kiln::scene s = kiln::load_gltf(asset_path);
    for (const kiln::quadric& q : s.quadrics) trace_fan(q);
  } catch (const kiln::error&) {
    // A clear refusal is the expected outcome for most inputs.
  }
  return 0;
}
