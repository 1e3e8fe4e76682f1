#include "job/memory_limit.h"

#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <sstream>

namespace kiln {

namespace {

std::string file_text(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream out;
  out << in.rdbuf();
  return out.str();
}

// This process's path in the cgroup hierarchy named by `controller` ("" for v2's unified one),
// from /proc/self/cgroup's "0::/path" or "4:memory:/path"; "/" when not listed.
std::string cgroup_path(const std::string& controller) {
  std::istringstream lines(file_text("/proc/self/cgroup"));
  for (std::string line; std::getline(lines, line);) {
    const size_t first = line.find(':'), second = line.find(':', first + 1);
    if (second != std::string::npos && line.substr(first + 1, second - first - 1) == controller)
      return line.substr(second + 1);
  }
  return "/";
}

// The lowest limit in `name` from the process's cgroup folder under root up to root itself: a
// parent's lower limit binds a child too. A container often mounts its own cgroup as root, so
// folders that do not exist are skipped. 0: none.
uint64_t lowest_cgroup_limit(const std::string& root, const std::string& path, const std::string& name) {
  uint64_t lowest = 0;
  std::string folder = root + (path == "/" ? "" : path);
  while (true) {
    if (const uint64_t limit = parse_cgroup_limit(file_text(folder + "/" + name)))
      lowest = lowest ? std::min(lowest, limit) : limit;
    if (folder.size() <= root.size()) return lowest;
    folder.resize(folder.rfind('/'));
  }
}

uint64_t lower_of(uint64_t a, uint64_t b) { return a == 0 ? b : b == 0 ? a : std::min(a, b); }

uint64_t physical_memory() {
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
  return pages > 0 && page > 0 ? uint64_t(pages) * uint64_t(page) : 0;
}

}  // namespace

uint64_t parse_cgroup_limit(const std::string& text) {
  const size_t digits = text.find_first_not_of("0123456789");
  if (digits == 0) return 0;  // "max", empty
  const unsigned long long value = std::strtoull(text.c_str(), nullptr, 10);
  // cgroup v1 writes "no limit" as a page-rounded LLONG_MAX.
  return value >= (uint64_t(1) << 62) ? 0 : uint64_t(value);
}

uint64_t usable_memory() {
  uint64_t usable = physical_memory();
  usable = lower_of(usable, lowest_cgroup_limit("/sys/fs/cgroup", cgroup_path(""), "memory.max"));
  usable = lower_of(
      usable, lowest_cgroup_limit("/sys/fs/cgroup/memory", cgroup_path("memory"), "memory.limit_in_bytes"));
  return usable;
}

uint64_t default_memory_budget() {
  const uint64_t usable = usable_memory();
  return usable ? usable / 10 * 9 : ~uint64_t(0);
}

}  // namespace kiln
