#!/bin/bash
# The build-option and packet runs of docs/performance.md (about 20 minutes on 2 loaded cores).
# Run from the repository root; writes json/<case>/ and summary.txt to docs/performance/build-options/
# (or OUT). KILN_BEFORE: kiln built from 7bed80f (before that change); KILN_AFTER: the build to measure.
set -e
HERE=$(cd "$(dirname "$0")" && pwd)
OUT=${OUT:-$HERE/../../docs/performance/build-options}; mkdir -p "$OUT"
B=${KILN_BEFORE:?kiln built at 7bed80f}; A=${KILN_AFTER:-build/renderer/app/kiln}
S=${BENCH_SCENES:-/tmp/kiln-bench-scenes}; mkdir -p "$S"; build/bench/make_bench_scenes "$S" --skip-4m >/dev/null
T=../shared/assets/ToyCar/glTF/ToyCar.gltf
ab() { /usr/bin/python3 "$HERE/bench_ab.py" "$OUT/json/$1" 3 "${@:2}"; }
{
  echo "## before / after / packets"
  for c in "demo scenes/cornell_box.gltf --width 1280 --height 960" "mesh_100k $S/mesh_100k.glb --width 1280 --height 960" \
           "instanced $S/instanced_1000x10k.glb" "toycar $T"; do
    set -- $c; echo "== $*"; ab "packets_$1" "${@:2}" -- before="$B" after="$A" packets="$A:--packets on"
  done
  echo "## BVH build quality and layout"
  for c in "mesh_100k $S/mesh_100k.glb" "mesh_1m $S/mesh_1m.glb" "instanced $S/instanced_1000x10k.glb"; do
    set -- $c; echo "== $*"
    ab "bvh_$1" "${@:2}" -- medium="$A" low="$A:--bvh-quality low" high="$A:--bvh-quality high" compact="$A:--bvh-compact"
  done
} 2>&1 | tee "$OUT/summary.txt"
