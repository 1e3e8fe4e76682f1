#!/usr/bin/env bash
# The README's second command: installs missing Debian packages, builds everything and runs the
# whole test suite (CTest over GoogleTest). .ci/run calls exactly this.
set -euo pipefail
cd "$(dirname "$0")/.."

tools/install_dependencies.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build
ctest --test-dir build --output-on-failure -j "$(nproc)"
