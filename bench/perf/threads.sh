#!/bin/bash
# Thread scaling of the render phase, before and after a change, in alternated rounds.
# usage: bench/perf/threads.sh ROUNDS BEFORE_KILN AFTER_KILN > runs.csv   (from the repository root)
# Per round, scene and binary: one 2-thread render, two 1-thread renders at once (each has a core,
# as the threads of a 2-thread render do) and one 1-thread render alone. kiln's own
# "render N s" is recorded (load, build and EXR writing excluded).
set -euo pipefail
rounds=$1 before=$2 after=$3
assets=${ASSETS:-../shared/assets}
scenes=("demo|scenes/cornell_box.gltf --width 1280 --height 960 --spp 4"
        "toycar|$assets/ToyCar/glTF/ToyCar.gltf --width 640 --height 480 --spp 4")
out=$(mktemp -d)
seconds() { grep -o 'render [0-9.]* s' | awk '{print $2}'; }
echo "round,scene,binary,two_threads,one_thread_beside_another,one_thread_alone"
for r in $(seq "$rounds"); do
  for entry in "${scenes[@]}"; do
    name=${entry%%|*}; args=${entry#*|}
    for bin in before after; do
      k=$before; [ $bin = after ] && k=$after
      two=$($k render $args -o $out/two.exr --threads 2 2>&1 | seconds)
      $k render $args -o $out/a.exr --threads 1 2>&1 | seconds > $out/a.t &
      b=$($k render $args -o $out/b.exr --threads 1 2>&1 | seconds)
      wait
      a=$(cat $out/a.t)
      alone=$($k render $args -o $out/alone.exr --threads 1 2>&1 | seconds)
      echo "$r,$name,$bin,$two,$(python3 -c "print(($a+$b)/2)"),$alone"
    done
  done
done
rm -rf "$out"
