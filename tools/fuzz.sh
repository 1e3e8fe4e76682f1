#!/usr/bin/env bash
# Fuzzes kiln's glTF/GLB loader with libFuzzer (clang-14 from Debian, ASan+UBSan).
#   tools/fuzz.sh [SECONDS]     default 300; the run's last status line gives executions and coverage
# Seeds: scenes/, tests/data/bad_gltf/ and, when present, ../shared/assets (files under 1 MiB).
# Findings land in fuzz/findings/; each one becomes a regression input in tests/data/fuzz_regressions/,
# which the normal test suite replays (tests/fuzz_regression_test.cpp).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-300}"

if ! command -v clang++-14 >/dev/null; then
  apt-get update -q && apt-get install -y -q clang-14
fi
tools/install_dependencies.sh
CC=clang-14 CXX=clang++-14 cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DKILN_FUZZ=ON \
  -DKILN_BUILD_TESTS=OFF -DKILN_SANITIZE=address,undefined >/dev/null
cmake --build build-fuzz --target fuzz_gltf_loader

corpus=fuzz/corpus/gltf_loader
mkdir -p "$corpus" fuzz/findings
seeds=(scenes tests/data/bad_gltf tests/data/fuzz_regressions)
[[ -d ../shared/assets ]] && seeds+=(../shared/assets)
find "${seeds[@]}" -type f \( -name '*.gltf' -o -name '*.glb' \) -size -1024k -exec cp -n {} "$corpus/" \; 2>/dev/null || true

ASAN_OPTIONS=detect_leaks=1:fast_unwind_on_malloc=0 LSAN_OPTIONS=suppressions=fuzz/lsan.supp UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 \
  build-fuzz/fuzz/fuzz_gltf_loader "$corpus" -dict=fuzz/gltf.dict -max_total_time="$seconds" \
  -max_len=262144 -rss_limit_mb=4096 -timeout=10 -artifact_prefix=fuzz/findings/ -print_final_stats=1
