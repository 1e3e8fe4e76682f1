#!/usr/bin/env bash
# Installs the Debian 12 packages kiln needs, and nothing when they are all present already.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config python3
  libembree-dev libtbb-dev libopenimageio-dev openimageio-tools libopenexr-dev
  libtinygltf-dev nlohmann-json3-dev libglm-dev libcli11-dev
  libgtest-dev libgmock-dev libbenchmark-dev
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi
echo "kiln: installing ${missing[*]}" >&2
sudo_cmd=()
[ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
