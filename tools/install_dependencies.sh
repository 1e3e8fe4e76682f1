#!/usr/bin/env bash
# Installs the Debian 12 packages kiln needs (or the packages named as arguments), and nothing
# when they are all present already. Packages' services are not started by the install.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config python3
  libembree-dev libtbb-dev libopenimageio-dev openimageio-tools libopenexr-dev libopencolorio-dev
  libtinygltf-dev libdraco-dev libmeshoptimizer-dev libpng-dev zlib1g-dev libjpeg-dev nlohmann-json3-dev libglm-dev libcli11-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  python3-dev pybind11-dev python3-numpy python3-pytest python3-openimageio python3-venv git
  clang-format-14
)
[ $# -eq 0 ] || packages=("$@")

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
# invoke-rc.d and deb-systemd-invoke consult /usr/sbin/policy-rc.d: exit 101 forbids starting a
# service, so a postinst leaves no daemon running (e.g. a system slurmd or munged). An existing
# policy is left as it is.
policy=/usr/sbin/policy-rc.d
if [ ! -e "$policy" ]; then
  "${sudo_cmd[@]}" sh -c "printf '#!/bin/sh\nexit 101\n' >$policy && chmod +x $policy"
  trap '"${sudo_cmd[@]}" rm -f "$policy"' EXIT
fi
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
