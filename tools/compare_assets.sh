#!/usr/bin/env bash
# Runs `kiln compare` (grid and adaptive grid against Embree) on every scene in scenes/ and every
# model in ../shared/assets, one summary line each; exits non-zero when any comparison disagrees
# or fails. Only an asset refused for an unsupported required extension (e.g. KHR_materials_clearcoat) is skipped;
# any other exit 1 or 2 (a loader regression, a usage error in the extra options) is a failure.
# Usage: tools/compare_assets.sh [extra kiln compare options, e.g. --width 256 --height 256]
set -uo pipefail
cd "$(dirname "$0")/.."
kiln=build/renderer/app/kiln
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
report=$scratch/report.json
errors=$scratch/stderr.txt
status=0

list_assets() {
  find scenes -maxdepth 1 \( -name '*.gltf' -o -name '*.glb' \) -print0 | sort -z
  if [ -d ../shared/assets ]; then
    find ../shared/assets -path '*/invalid' -prune -o \( -name '*.gltf' -o -name '*.glb' \) -print0 | sort -z
  fi
}

while IFS= read -r -d '' file; do
  for accel in grid adaptive-grid; do
    rm -f "$report"  # a run that fails must not be summarised from the previous asset's report
    "$kiln" compare "$file" --accel "$accel" --json "$report" -q "$@" 2>"$errors"
    rc=$?
    if [ "$rc" -eq 1 ] || [ "$rc" -eq 2 ]; then
      if [ "$rc" -eq 2 ] && grep -q '/extensionsRequired/.*required extension .* is not supported' "$errors"; then
        echo "$file $accel: skipped ($(head -n 1 "$errors"))"
      else
        echo "$file $accel: FAILED, exit $rc: $(head -n 1 "$errors")"
        status=1
      fi
      continue
    fi
    [ "$rc" -ne 0 ] && status=1
    if [ ! -s "$report" ]; then
      echo "$file $accel: FAILED, exit $rc without a report: $(head -n 1 "$errors")"
      status=1
      continue
    fi
    python3 - "$report" "$file" "$accel" "$rc" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
k = r["rays"].values()
print(f"{sys.argv[2]} {sys.argv[3]}: exit {sys.argv[4]}, mismatches {r['mismatches']}, rays {sum(v['rays'] for v in k)}, "
      f"ties {sum(v['ties'] for v in k)}, edge cases {sum(v['edge_cases'] for v in k)}, "
      f"max |dt|/t {max(v['max_relative_dt'] for v in k):.2g}, differing pixels {r['image']['differing_pixels']}")
PY
  done
done < <(list_assets)
exit $status
