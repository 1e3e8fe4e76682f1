#!/usr/bin/env bash
# The README's commands are idempotent: with every package present, the dependency step never calls
# apt-get or sudo (both are replaced by failing stand-ins here), and a built tree has nothing left
# to rebuild for the kiln target.
# Usage: setup_idempotence_test.sh SOURCE_DIR BUILD_DIR
set -euo pipefail
source_dir="$1"
build_dir="$2"
fake_bin="$(mktemp -d)"
trap 'rm -rf "$fake_bin"' EXIT
for tool in apt-get apt sudo; do
  printf '#!/bin/sh\necho "%s must not run when everything is installed" >&2\nexit 97\n' "$tool" >"$fake_bin/$tool"
  chmod +x "$fake_bin/$tool"
done
PATH="$fake_bin:$PATH" "$source_dir/tools/install_dependencies.sh"
plan="$(cmake --build "$build_dir" --target kiln -- -n)"
if ! grep -q "no work to do" <<<"$plan"; then
  echo "the kiln target is not up to date after a build:" >&2
  echo "$plan" >&2
  exit 1
fi
echo "install_dependencies.sh installed nothing; kiln is up to date"
