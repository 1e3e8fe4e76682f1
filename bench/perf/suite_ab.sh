#!/bin/bash
# The asset suite's CPU time under two builds: every shipped scene and each sample model's first
# glTF (or GLB) rendered by A then B, file by file, so load on the machine falls on both alike.
# Usage: bench/perf/suite_ab.sh KILN_A KILN_B RENDER_ARGS...   (e.g. --width 160 --height 120 --threads 1)
# Prints the sum of user CPU seconds of each build.
A=$1; B=$2; shift 2
T=${TMPDIR:-/tmp}
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
files=$(ls "$ROOT"/scenes/*.gltf
  for d in "$ROOT"/../shared/assets/*/; do ls "$d"glTF/*.gltf "$d"glTF-Binary/*.glb 2>/dev/null | head -1; done)
sum_a=0; sum_b=0
for f in $files; do
  for v in A B; do
    /usr/bin/time -f "%U" -o "$T/suite_time.txt" "${!v}" render "$f" -o "$T/suite_ab.exr" "$@" >/dev/null 2>&1
    t=$(tail -1 "$T/suite_time.txt")
    if [ $v = A ]; then sum_a=$(echo "$sum_a + $t" | bc); else sum_b=$(echo "$sum_b + $t" | bc); fi
  done
done
echo "A $sum_a s  B $sum_b s"
