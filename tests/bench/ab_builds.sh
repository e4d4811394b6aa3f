#!/usr/bin/env bash
# Two builds of sphclip side by side on the dfsph scenes: whole runs,
# interleaved round by round, each with 2 threads and no pictures. Prints
# CSV: wall time, steps, and the density and divergence solves' iterations
# a step (stats.csv's mean over the frames after the first).
# Used for the dfsph walls' change (docs/validation.md, "The deep tank's
# blow-up: the walls' term"): build the commit before a change in a second
# folder (git worktree add ../before HEAD~1; cmake ...; cmake --build) and
# compare.
# usage: tests/bench/ab_builds.sh SPHCLIP_A SPHCLIP_B [ROUNDS]
set -euo pipefail
a=${1:?usage: ab_builds.sh SPHCLIP_A SPHCLIP_B [ROUNDS]}
b=${2:?usage: ab_builds.sh SPHCLIP_A SPHCLIP_B [ROUNDS]}
rounds=${3:-3}
here="$(cd "$(dirname "$0")" && pwd)"
root="$here/../.."
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cases=("$root/scenes/first_clip_3d.json|"
       "$here/peers/splishsplash_dam_break.json|--duration 1.0"
       "$root/scenes/dam_break_water_2d_dfsph.json|"
       "$root/scenes/dam_break_water_3d_dfsph.json|")
echo "# $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//'), $(nproc) CPUs, load $(cut -d' ' -f1-3 /proc/loadavg)"
echo "case,round,build,wall_s,steps,pressure_iterations_a_step,divergence_iterations_a_step"
for c in "${cases[@]}"; do
    scene=${c%%|*}
    read -r -a extra <<<"${c#*|}"
    for round in $(seq 1 "$rounds"); do
        for build in A B; do
            program=$a
            [ "$build" = B ] && program=$b
            rm -rf "$work/out"
            t0=$(date +%s.%N)
            "$program" run "$scene" "${extra[@]}" --no-png --no-mp4 --threads 2 --out "$work/out" \
                >"$work/log" 2>&1 || { cat "$work/log"; exit 1; }
            t1=$(date +%s.%N)
            steps=$(tail -1 "$work/out/stats.csv" | cut -d, -f3)
            iterations=$(awk -F, 'NR > 2 { p += $14; d += $15; n++ }
                                  END { if (n) printf "%.2f,%.2f", p / n, d / n }' "$work/out/stats.csv")
            echo "$(basename "$scene" .json),$round,$build,$(echo "$t1 - $t0" | bc),$steps,$iterations"
        done
    done
done
echo "# load at the end $(cut -d' ' -f1-3 /proc/loadavg)"
