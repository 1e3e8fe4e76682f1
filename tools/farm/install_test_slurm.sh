#!/usr/bin/env bash
# Installs the Debian 12 packages the single-node Slurm test needs (slurmctld, slurmd, the client
# commands and munge), and nothing when they are all present already. The packages' own services
# are kept from starting (policy-rc.d answers 101 for the duration of the install) and any daemon
# the install started anyway is stopped, so nothing system-wide is left listening on Slurm's or
# munge's default ports and sockets: tools/farm/start_test_slurm.sh runs private copies instead.
set -euo pipefail

packages=(slurmctld slurmd slurm-client munge)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi
echo "kiln farm: installing ${missing[*]}" >&2
sudo_cmd=()
[ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
export DEBIAN_FRONTEND=noninteractive

# invoke-rc.d consults /usr/sbin/policy-rc.d: exit 101 means "action forbidden", so postinst
# scripts install the services without starting them. An existing policy is left as it was.
policy=/usr/sbin/policy-rc.d
own_policy=0
if [ ! -e "$policy" ]; then
  "${sudo_cmd[@]}" sh -c "printf '#!/bin/sh\nexit 101\n' >$policy && chmod +x $policy"
  own_policy=1
fi
cleanup() { [ "$own_policy" -eq 0 ] || "${sudo_cmd[@]}" rm -f "$policy"; }
trap cleanup EXIT

"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"

# Belt and braces for systems whose init ignores policy-rc.d (systemd with the units enabled).
if command -v systemctl >/dev/null && [ -d /run/systemd/system ]; then
  for unit in slurmctld slurmd munge; do
    "${sudo_cmd[@]}" systemctl disable --now "$unit" >/dev/null 2>&1 || true
  done
fi
