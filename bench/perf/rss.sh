#!/bin/bash
# usage: bench/perf/rss.sh LABEL kiln-args...   prints label, max RSS kB, user+sys s
L=$1; shift
/usr/bin/time -v "$@" 2>${TMPDIR:-/tmp}/time_$$.txt >/dev/null
rc=$?
rss=$(grep 'Maximum resident' ${TMPDIR:-/tmp}/time_$$.txt | awk '{print $NF}')
u=$(grep 'User time' ${TMPDIR:-/tmp}/time_$$.txt | awk '{print $NF}')
s=$(grep 'System time' ${TMPDIR:-/tmp}/time_$$.txt | awk '{print $NF}')
w=$(grep 'Elapsed' ${TMPDIR:-/tmp}/time_$$.txt | awk '{print $NF}')
echo "$L rc=$rc rss_kB=$rss cpu_s=$(echo "$u + $s" | bc) wall=$w"
