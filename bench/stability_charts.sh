#!/usr/bin/env bash
# Builds the stability study, runs it into build/bench-results/stability/ and renders charts 4
# and 5 there (docs/stability.md). Usage: bench/stability_charts.sh [BUILD_DIR]
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$root/build}"
out="$build/bench-results/stability"
if [[ ! -f "$build/CMakeCache.txt" ]]; then
  cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release
fi
cmake --build "$build" --target stability_study
mkdir -p "$out"
"$build/bench/stability_study" "$out"
# matplotlib comes from Debian's python3-matplotlib, installed for the system interpreter.
/usr/bin/python3 "$root/bench/charts/stability_charts.py" "$out"
echo "charts in $out"
