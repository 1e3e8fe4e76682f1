#!/bin/bash
# The cost of motion blur: each animated asset at frame 12, 640x480, 16 spp, 2 threads, without
# and with --shutter -0.25,0.25 (a 180° shutter), alternated, two rounds. Prints kiln's own load
# (posing the frame and the shutter's steps), build and render times and the steps it chose.
# Run from the repository root after a release build.
set -e
K=${KILN:-build/renderer/app/kiln}
A=${ASSETS:-../shared/assets}
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
for round in 1 2; do
  for asset in BoxAnimated CesiumMan BrainStem; do
    for shutter in "" "--shutter -0.25,0.25"; do
      # shellcheck disable=SC2086
      line=$("$K" render "$A/$asset/glTF-Binary/$asset.glb" -o "$OUT/b.exr" --width 640 --height 480 \
        --frame 12 --spp 16 --threads 2 $shutter 2>&1 | tail -1)
      steps=$(iinfo -v "$OUT/b.exr" | sed -n 's/.*kiln\/shutter_steps: "\(.*\)"/\1/p')
      echo "round $round $asset ${shutter:-(no blur)} steps=${steps:-0}: $(echo "$line" | sed 's/.*: load/load/; s/ (.*//')"
    done
  done
done
