#!/bin/sh
# Soak of accelerator::occluded_batch (Embree ray packets, rtcOccluded16/8/4): runs the unit test
# that fires 6000 random batches on two threads at once over the quadric scene and an instanced
# lattice (both with motion blur), RUNS times in fresh processes of REPEAT test runs each, every
# process under a time limit, and counts the runs that failed and the processes that hung (did not
# finish within LIMIT seconds: the way rtcOccluded1M failed, docs/performance.md). Speed is not
# its business; `kiln bench` times the batch. Prints one summary line; exit 1 on any failure or hang.
# Usage: bench/perf/occlusion_soak.sh [RUNS=100] [REPEAT=10] [LIMIT=120]   (from the repository root)
set -u
runs=${1:-100}
repeat=${2:-10}
limit=${3:-120}
test_binary=${KILN_BUILD:-build}/renderer/accel/embree/embree_occlusion_batch_test
[ -x "$test_binary" ] || { echo "occlusion_soak: no $test_binary (build target embree_occlusion_batch_test)" >&2; exit 2; }
failed=0 hung=0 passed=0
start=$(date +%s)
i=0
while [ "$i" -lt "$runs" ]; do
  i=$((i + 1))
  out=$(timeout "$limit" "$test_binary" --gtest_filter='*thousands_of_batches*' --gtest_repeat="$repeat" 2>&1)
  rc=$?
  if [ "$rc" -eq 124 ]; then
    hung=$((hung + 1))
    echo "occlusion_soak: process $i did not finish within ${limit} s" >&2
  elif [ "$rc" -ne 0 ]; then
    failed=$((failed + 1))
    echo "$out" | grep -E 'Failure|Which is|FAILED' | head -5 >&2
  fi
  passed=$((passed + $(echo "$out" | grep -c '^\[       OK \]')))
done
seconds=$(($(date +%s) - start))
echo "occlusion_soak: $runs processes x $repeat runs: $passed test runs passed ($((passed * 12000)) batches)," \
  "$failed processes failed, $hung hung; ${seconds} s"
[ "$failed" -eq 0 ] && [ "$hung" -eq 0 ]
