#!/usr/bin/env bash
# The double-precision passes of a portable build with and without their
# clones (sph/vector_clones.hpp), against a native build, on the flows of
# sphclip_bench_flow; one binary after the other in each round, so the
# three share the machine's state (docs/benchmarks.md, "Single precision
# on each processor").
#
#   tests/bench/double_clones.sh NATIVE_BENCH PORTABLE_BEFORE_BENCH PORTABLE_BENCH ROUNDS CSV
#
# Each *_BENCH is a sphclip_bench_flow; PORTABLE_BEFORE_BENCH one built
# before the clones (or any third build to compare).
set -euo pipefail
native=${1:?usage: double_clones.sh NATIVE BEFORE PORTABLE ROUNDS CSV}
before=${2:?}
portable=${3:?}
rounds=${4:-3}
csv=${5:?}
repo=$(cd "$(dirname "$0")/../.." && pwd)
work=$(mktemp -d /tmp/sphclip-clones.XXXXXX)
trap 'rm -rf "$work"' EXIT
export GOMP_SPINCOUNT=${GOMP_SPINCOUNT:-10000}
{
    echo "# tests/bench/double_clones.sh, $(date -u +%Y-%m-%dT%H:%MZ), $(lscpu | sed -n 's/^Model name: *//p'), $(nproc) cores, load at start $(cut -d' ' -f1-3 /proc/loadavg)"
    echo "# builds: native = -DSPHCLIP_ARCH=native; portable_before = x86-64-v2 without clones; portable = x86-64-v2 with clones"
} >"$csv"
header_done=0
for r in $(seq 1 "$rounds"); do
    for pair in "native:$native" "portable_before:$before" "portable:$portable"; do
        name=${pair%%:*}
        bench=${pair#*:}
        "$bench" --cases dam_2d_20k,dsph_2d_20k,dam_3d_100k --precision double --threads 2 \
            --rounds 1 --scenes "$repo/scenes" --csv "$work/one.csv" >"$work/one.log"
        grep '^# ' "$work/one.csv" | sed "s/^# /# $name round $r: /" >>"$csv"
        if [[ $header_done == 0 ]]; then
            grep -v '^#' "$work/one.csv" | head -1 | sed 's/^/build,round,/' >>"$csv"
            header_done=1
        fi
        grep -v '^#' "$work/one.csv" | tail -n +2 | sed "s/^/$name,$r,/" >>"$csv"
        grep -v '^#' "$work/one.csv" | tail -n +2 | awk -F, -v n="$name" -v r="$r" '{printf "%-16s round %s %-12s %s M particle-steps/s\n", n, r, $1, $9/1e6}'
    done
done
echo "# load at end $(cut -d' ' -f1-3 /proc/loadavg)" >>"$csv"
