#!/bin/bash
# Alternated A/B renders: each round runs every variant once, in order.
# Usage: bench/perf/render_ab.sh ROUNDS COMMON_RENDER_ARGS... -- 'LABEL|ENV|EXTRA ARGS' ...
# Prints one line per run: round, label, process CPU s (user+sys), wall s, render-phase wall s.
# ENV is a list of NAME=VALUE (or empty), e.g. measurement-only switches a build was patched with
# (docs/performance.md, "Embree scene and query flags"); KILN=PATH in it runs that build for the
# variant (before/after builds alternated), else $KILN or build/renderer/app/kiln.
R=$1; shift; ARGS=(); while [ "$1" != "--" ]; do ARGS+=("$1"); shift; done; shift
T=${TMPDIR:-/tmp}
for r in $(seq "$R"); do for v in "$@"; do
  IFS='|' read -r label envs extra <<< "$v"
  K=${KILN:-build/renderer/app/kiln}
  for e in $envs; do [[ $e == KILN=* ]] && K=${e#KILN=}; done
  env $envs /usr/bin/time -f "%U %S %e" -o "$T/ab_time.txt" $K render "${ARGS[@]}" $extra -o "$T/ab_$label.exr" 2> "$T/ab_log.txt"
  read -r u s w < "$T/ab_time.txt"
  echo "$r $label $(echo "$u + $s" | bc) $w $(grep -o 'render [0-9.]* s' "$T/ab_log.txt" | awk '{print $2}')"
done; done
