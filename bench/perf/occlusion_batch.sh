#!/bin/sh
# Shadow rays through accelerator::occluded_batch (Embree ray packets) against the single-ray
# occluded() and the bare rtcOccluded1 loop: `kiln bench` on ToyCar (the peer benchmark's wrapper
# with its point light) and the peer quadric scene at 640x480, 16 spp, two threads, the file's
# lights only, ROUNDS rounds alternating the two scenes; within each run kiln bench alternates the
# three loops over the same recorded shadow rays. JSON, CSV and console output go to OUT.
# Usage: bench/perf/occlusion_batch.sh [OUT=build/bench-results/occlusion-batch] [ROUNDS=3]
#        (from the repository root; ToyCar from ../shared/assets)
set -eu
out=${1:-build/bench-results/occlusion-batch}
rounds=${2:-3}
kiln=${KILN:-build/renderer/app/kiln}
mkdir -p "$out"
out_abs=$(cd "$out" && pwd)
asset=$(cd .. && pwd)/shared/assets/ToyCar/glTF/ToyCar.gltf
toycar=$(cd bench/peers && /usr/bin/python3 -c "import peer_bench; print(peer_bench.toycar_wrapper('$asset', '$out_abs', 640, 480))")
common="--lighting file --max-depth 8 --width 640 --height 480 --spp 16 --threads 2 --repeat 3"
round=1
while [ "$round" -le "$rounds" ]; do
  # shellcheck disable=SC2086
  "$kiln" bench "$toycar" --allow-outside-files $common --label toycar-16spp \
    --json "$out/toycar_$round.json" --csv "$out/toycar_$round.csv" | tee -a "$out/summary.txt"
  # shellcheck disable=SC2086
  "$kiln" bench scenes/peer_quadrics.gltf $common --label quadrics-16spp \
    --json "$out/quadrics_$round.json" --csv "$out/quadrics_$round.csv" | tee -a "$out/summary.txt"
  round=$((round + 1))
done
