#!/usr/bin/env bash
# Runs `kiln compare` (grid and adaptive grid against Embree) on every scene in scenes/ and every
# model in ../shared/assets, one summary line each; exits non-zero when any comparison disagrees.
# Usage: tools/compare_assets.sh [extra kiln compare options, e.g. --width 256 --height 256]
set -uo pipefail
cd "$(dirname "$0")/.."
kiln=build/renderer/app/kiln
report=$(mktemp)
trap 'rm -f "$report"' EXIT
status=0
files=$(ls scenes/*.gltf scenes/*.glb 2>/dev/null
        [ -d ../shared/assets ] && find ../shared/assets -path '*/invalid' -prune -o \( -name '*.gltf' -o -name '*.glb' \) -print | sort)
for file in $files; do
  for accel in grid adaptive-grid; do
    "$kiln" compare "$file" --accel "$accel" --json "$report" -q "$@" 2>/dev/null
    rc=$?
    if [ "$rc" -eq 2 ]; then echo "$file $accel: not loadable (unsupported input)"; continue; fi
    [ "$rc" -ne 0 ] && status=1
    python3 - "$report" "$file" "$accel" "$rc" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
k = r["rays"].values()
print(f"{sys.argv[2]} {sys.argv[3]}: exit {sys.argv[4]}, mismatches {r['mismatches']}, rays {sum(v['rays'] for v in k)}, "
      f"ties {sum(v['ties'] for v in k)}, edge cases {sum(v['edge_cases'] for v in k)}, "
      f"max |dt|/t {max(v['max_relative_dt'] for v in k):.2g}, differing pixels {r['image']['differing_pixels']}")
PY
  done
done
exit $status
