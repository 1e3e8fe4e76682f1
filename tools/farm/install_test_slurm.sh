#!/usr/bin/env bash
# Installs the Debian 12 packages the single-node Slurm test needs (slurmctld, slurmd, the client
# commands and munge), and nothing when they are all present already. Their services are not
# started (see tools/install_dependencies.sh): tools/farm/test_slurm.sh runs private daemons, on
# their own ports and munge socket, which would not clash with system ones anyway.
set -euo pipefail
exec "$(dirname "$0")/../install_dependencies.sh" slurmctld slurmd slurm-client munge
