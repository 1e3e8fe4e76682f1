#!/usr/bin/env bash
# Every tracked C++ file is formatted as .clang-format says, by Debian 12's clang-format 14 (the
# version tools/install_dependencies.sh installs: another version formats some lines differently).
# To fix: git ls-files '*.cpp' '*.h' | xargs clang-format-14 -i
# usage: check_format.sh REPO_ROOT
set -euo pipefail
cd "$1"
format=${KILN_CLANG_FORMAT:-/usr/bin/clang-format-14}
if [ ! -x "$format" ]; then
  echo "format: $format not found (tools/install_dependencies.sh installs clang-format-14)" >&2
  exit 1
fi
mapfile -t files < <(git ls-files '*.cpp' '*.h')
[ ${#files[@]} -gt 0 ] || { echo "format: no C++ files found under $1" >&2; exit 1; }
"$format" --dry-run --Werror "${files[@]}"
echo "format: ${#files[@]} files follow .clang-format"
