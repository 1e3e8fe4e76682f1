#!/bin/bash
# kiln's hit record against the bare Embree loop, before (KILN_BEFORE) and after this change, in
# alternated rounds (about 6 minutes on 2 cores). Run from the repository root; writes
# json/<case>/ and summary.txt to docs/performance/traversal/ (or OUT).
# usage: KILN_BEFORE=/path/to/old/kiln bench/perf/traversal_ab.sh
set -e
HERE=$(cd "$(dirname "$0")" && pwd)
OUT=${OUT:-$HERE/../../docs/performance/traversal}; mkdir -p "$OUT"
B=${KILN_BEFORE:?kiln built at the commit before}; A=${KILN_AFTER:-build/renderer/app/kiln}
S=${BENCH_SCENES:-/tmp/kiln-bench-scenes}; mkdir -p "$S"; build/bench/make_bench_scenes "$S" --skip-4m >/dev/null
T=../shared/assets/ToyCar/glTF/ToyCar.gltf
AB="$HERE/bench_ab.py"
{
  for c in "demo scenes/cornell_box.gltf --width 1280 --height 960" "mesh_100k $S/mesh_100k.glb --width 1280 --height 960" \
           "instanced $S/instanced_1000x10k.glb" "toycar $T"; do
    set -- $c; echo "== $*"
    /usr/bin/python3 "$AB" "$OUT/json/$1" 3 "${@:2}" -- before="$B" after="$A" packets="$A:--packets on"
  done
} 2>&1 | tee "$OUT/summary.txt"
