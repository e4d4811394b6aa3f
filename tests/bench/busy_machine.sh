#!/usr/bin/env bash
# The OpenMP wait policy on a quiet and on a busy machine (issue 22, item 4;
# docs/benchmarks.md, "Busy machines"): sphclip_bench_flow's cases under each
# policy, with 0 and 1 (and, with --both, 2) competing busy processes.
#
#   tests/bench/busy_machine.sh BUILD_DIR [CASES] [STEPS] > table.md
#
# Every row is a separate process, since libgomp reads the policy at start.
set -euo pipefail
build=${1:?usage: busy_machine.sh BUILD_DIR [CASES] [STEPS]}
cases=${2:-dam_2d_5k,dfsph_2d_5k}
steps=${3:-200}
loads=(0 1)
[ "${4:-}" = "--both" ] && loads+=(2)
bench="$build/sphclip_bench_flow"
policies=("libgomp default" "OMP_WAIT_POLICY=passive" "GOMP_SPINCOUNT=1000"
          "GOMP_SPINCOUNT=10000" "GOMP_SPINCOUNT=100000")
echo "# $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2-), $(nproc) CPUs, load $(cut -d' ' -f1-3 /proc/loadavg)"
for load in "${loads[@]}"; do
    for policy in "${policies[@]}"; do
        echo "## policy: $policy, competing busy processes: $load"
        if [ "$policy" = "libgomp default" ]; then
            env -u OMP_WAIT_POLICY -u GOMP_SPINCOUNT "$bench" --cases "$cases" --steps "$steps" \
                --rounds 3 --load "$load" --threads 1,2 --precision single,double
        else
            env -u OMP_WAIT_POLICY -u GOMP_SPINCOUNT "$policy" "$bench" --cases "$cases" \
                --steps "$steps" --rounds 3 --load "$load" --threads 1,2 --precision single,double
        fi
    done
done
