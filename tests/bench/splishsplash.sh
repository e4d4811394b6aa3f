#!/usr/bin/env bash
# sphclip against SPlisHSPlasH on SPlisHSPlasH's own DFSPH dam break (issue 22,
# item 6; docs/benchmarks.md, "Against SPlisHSPlasH"): both from rest to the
# same simulated time, interleaved over ROUNDS rounds with THREADS OpenMP
# threads each; prints each run's wall seconds (the whole process: set-up,
# stepping, no output files but sphclip's stats) and sphclip's steps.
#
#   tests/bench/splishsplash.sh SPHCLIP SPHSIMULATOR SPLISH_SOURCE [STOP_AT] [ROUNDS] [THREADS]
#
# SPHSIMULATOR is SPlisHSPlasH's bin/SPHSimulator built from SPLISH_SOURCE
# (its repository, in a scratch folder outside this one); the scene is its
# data/Scenes/DamBreakModel.json, and sphclip's the same case,
# tests/bench/peers/splishsplash_dam_break.json. A first, untimed run of
# each builds SPlisHSPlasH's boundary cache and warms the file cache.
set -euo pipefail
sphclip=${1:?usage: splishsplash.sh SPHCLIP SPHSIMULATOR SPLISH_SOURCE [STOP_AT] [ROUNDS] [THREADS]}
simulator=${2:?SPHSIMULATOR}
source_dir=${3:?SPLISH_SOURCE}
stop_at=${4:-1.0}
rounds=${5:-3}
threads=${6:-2}
here=$(cd "$(dirname "$0")" && pwd)
# SPlisHSPlasH reads a relative path from its own folder.
scene="$(cd "$source_dir" && pwd)/data/Scenes/DamBreakModel.json"
ours="$here/peers/splishsplash_dam_break.json"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

peer() {
    OMP_NUM_THREADS=$threads "$simulator" --no-gui --no-initial-pause --stopAt "$stop_at" \
        --output-dir "$work/peer" "$scene" > "$work/peer.log" 2>&1
}
mine() {
    "$sphclip" run "$ours" --threads "$threads" --duration "$stop_at" --no-png --no-mp4 \
        --out "$work/ours" > "$work/ours.log" 2>&1
}
seconds() { local t0 t1; t0=$(date +%s.%N); "$@"; t1=$(date +%s.%N); echo "$t1 - $t0" | bc; }

echo "# $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//'), $(nproc) CPUs, load $(cut -d' ' -f1-3 /proc/loadavg); $threads threads; to t = $stop_at s"
peer
mine
echo "round,SPlisHSPlasH_s,sphclip_s,SPlisHSPlasH_steps,sphclip_steps,SPlisHSPlasH_pressure_iterations_a_step,sphclip_pressure_iterations_a_step"
for round in $(seq 1 "$rounds"); do
    p=$(seconds peer)
    o=$(seconds mine)
    steps=$(tail -1 "$work/ours/stats.csv" | cut -d, -f3)
    iterations=$(awk -F, 'NR > 2 { s += $14; n++ } END { if (n) printf "%.1f", s / n }' "$work/ours/stats.csv")
    # SPlisHSPlasH's counters at its end: the steps' summed and mean size, iterations a step.
    peer_steps=$(awk '/Total number: Time step size/ { t = $NF } /Average number: Time step size/ { a = $NF }
                      END { if (a > 0) printf "%.0f", t / a }' "$work/peer.log")
    peer_iterations=$(awk '/Average number: DFSPH - iterations:/ { printf "%.1f", $NF }' "$work/peer.log")
    echo "$round,$p,$o,$peer_steps,$steps,$peer_iterations,$iterations"
done
echo "# load at the end $(cut -d' ' -f1-3 /proc/loadavg)"
