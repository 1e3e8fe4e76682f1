// The default memory budget of a job (--max-memory): 90% of the memory this process may use, the
// machine's physical memory or its cgroup's limit (v2 memory.max, v1 memory.limit_in_bytes) when
// that is lower. The 10% left is for what the estimates do not count (code, stacks, the
// allocator's slack, other processes). Depends on the standard library and Linux's /proc and
// /sys only.
#pragma once

#include <cstdint>
#include <string>

namespace kiln {

// The bytes a cgroup limit file holds ("max" and v1's "no limit" sentinel read as none); 0: none.
uint64_t parse_cgroup_limit(const std::string& text);

// min(physical memory, cgroup limit) in bytes; 0 when neither can be read.
uint64_t usable_memory();

// 90% of usable_memory(), or unlimited (~0) when it is unknown.
uint64_t default_memory_budget();

}  // namespace kiln
