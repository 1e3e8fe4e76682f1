// The stability study: where each self-intersection offset and each ray solver fails, as CSV for
// charts 4 and 5 (bench/charts/). A measurement program, not a test: tests/stability asserts on
// the same experiments (bench/stability/). Fixed seeds, so a rerun gives the same rates.
//
//   stability_study OUT_DIR [--rays N] [--solver-rays N] [--torus-rays N]
//
// writes OUT_DIR/self_intersection.csv, sphere_solvers.csv and torus_solvers.csv.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "stability/self_intersection.h"
#include "stability/solver_accuracy.h"

namespace {

using namespace kiln::bench;

struct options {
  std::string out_dir;
  int rays = 4000;
  int solver_rays = 4000;
  int torus_rays = 400;
};

int usage() {
  std::fprintf(stderr, "usage: stability_study OUT_DIR [--rays N] [--solver-rays N] [--torus-rays N]\n");
  return 2;
}

bool parse(int argc, char** argv, options& o) {
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto count = [&](int& target) {
      if (i + 1 >= argc) return false;
      target = std::atoi(argv[++i]);
      return target > 0;
    };
    if (a == "--rays") {
      if (!count(o.rays)) return false;
    } else if (a == "--solver-rays") {
      if (!count(o.solver_rays)) return false;
    } else if (a == "--torus-rays") {
      if (!count(o.torus_rays)) return false;
    } else if (o.out_dir.empty() && !a.empty() && a[0] != '-') {
      o.out_dir = a;
    } else {
      return false;
    }
  }
  return !o.out_dir.empty();
}

std::vector<double> decades(int lo, int hi) {
  std::vector<double> v;
  for (int e = lo; e <= hi; ++e) v.push_back(std::pow(10.0, e));
  return v;
}

void self_intersection_study(const options& o, std::ofstream& csv) {
  csv << "sweep,shape,method,epsilon,scale,translation,shadow_rays,acne,acne_rate,gap_rays,leaks,leak_rate,"
         "gap_self_hits,ns_per_shadow_ray\n";
  std::vector<offset_method> methods;
  for (double eps : decades(-7, -2)) methods.push_back({eps});
  methods.push_back({0.0});
  std::vector<std::pair<const char*, placement>> points;
  for (double s : decades(-4, 7)) points.push_back({"scale", {s, 0.0}});
  points.push_back({"translation", {1.0, 0.0}});
  for (double t : decades(0, 7)) points.push_back({"translation", {1.0, t}});
  for (test_shape shape : {test_shape::plane, test_shape::sphere})
    for (const offset_method& m : methods)
      for (const auto& [sweep, where] : points) {
        const self_intersection_result r = measure_self_intersection(shape, where, m, o.rays, 11);
        char line[512];
        std::snprintf(line, sizeof line, "%s,%s,%s,%.1e,%.1e,%.1e,%lld,%lld,%.6g,%lld,%lld,%.6g,%lld,%.1f\n",
                      sweep, shape_name(shape), method_name(m).c_str(), m.epsilon, where.scale,
                      where.translation, (long long)r.shadow_rays, (long long)r.acne, r.acne_rate(),
                      (long long)r.gap_rays, (long long)r.leaks, r.leak_rate(), (long long)r.gap_self_hits,
                      r.ns_per_shadow_ray);
        csv << line;
      }
}

void write_accuracy(std::ofstream& csv, const char* shape, const char* solver, const char* rays_kind,
                    double distance, const solver_accuracy& a) {
  char line[512];
  std::snprintf(line, sizeof line, "%s,%s,%s,%.1e,%lld,%lld,%lld,%lld,%lld,%.6g,%.6g,%.6g,%.1f\n", shape,
                solver, rays_kind, distance, (long long)a.rays, (long long)a.reference_hits,
                (long long)a.missed, (long long)a.invented, (long long)a.wrong, a.miss_rate(),
                a.failure_rate(), a.max_error, a.ns_per_ray);
  csv << line;
}

const char* accuracy_header =
    "shape,solver,rays_kind,distance,rays,reference_hits,missed,invented,wrong,miss_rate,failure_rate,"
    "max_error,ns_per_ray\n";

void sphere_study(const options& o, std::ofstream& csv) {
  csv << accuracy_header;
  std::vector<double> distances = decades(1, 7);
  distances.insert(distances.begin(), 1.5);
  for (sphere_solver s : {sphere_solver::naive_float, sphere_solver::naive_double,
                          sphere_solver::stable_float, sphere_solver::stable_double, sphere_solver::kiln})
    for (double d : distances)
      write_accuracy(csv, "sphere", solver_name(s), "toward", d,
                     measure_sphere_solver(s, d, o.solver_rays, 99));
}

void torus_study(const options& o, std::ofstream& csv) {
  csv << accuracy_header;
  std::vector<double> distances = decades(1, 7);
  distances.insert(distances.begin(), 2.0);
  for (bool grazing : {false, true})
    for (double d : distances) {
      const auto results = measure_torus_solvers(d, grazing, o.torus_rays, 5);
      for (int k = 0; k < 3; ++k)
        write_accuracy(csv, "torus", solver_name(torus_solver(k)), grazing ? "grazing" : "random", d,
                       results[size_t(k)]);
      std::fprintf(stderr, "torus %s %.0e done\n", grazing ? "grazing" : "random", d);
    }
}

}  // namespace

int main(int argc, char** argv) {
  options o;
  if (!parse(argc, argv, o)) return usage();
  std::filesystem::create_directories(o.out_dir);
  const std::filesystem::path dir(o.out_dir);
  {
    std::ofstream csv(dir / "self_intersection.csv");
    self_intersection_study(o, csv);
  }
  std::fprintf(stderr, "self-intersection done\n");
  {
    std::ofstream csv(dir / "sphere_solvers.csv");
    sphere_study(o, csv);
  }
  std::fprintf(stderr, "sphere solvers done\n");
  {
    std::ofstream csv(dir / "torus_solvers.csv");
    torus_study(o, csv);
    if (!csv) {
      std::fprintf(stderr, "stability_study: cannot write %s\n", (dir / "torus_solvers.csv").c_str());
      return 1;
    }
  }
  return 0;
}
