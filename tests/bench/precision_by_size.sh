#!/usr/bin/env bash
# wcsph's single- against double-precision passes on the shipped 3D water
# dam break at several spacings, from rest (docs/benchmarks.md, "Single
# precision, the 3D default"): ROUNDS rounds, the two precisions interleaved
# at each size, THREADS threads. Prints a line per run: round, spacing,
# fluid particles, precision, particle-steps per second (sphclip's own
# figure, the simulated steps only).
#
#   tests/bench/precision_by_size.sh SPHCLIP [ROUNDS] [THREADS] [SCENE]
set -euo pipefail
sphclip=$(cd "$(dirname "${1:?usage: precision_by_size.sh SPHCLIP [ROUNDS] [THREADS] [SCENE]}")" && pwd)/$(basename "$1")
rounds=${2:-2}
threads=${3:-2}
here=$(cd "$(dirname "$0")" && pwd)
scene=${4:-"$here/../../scenes/dam_break_water_3d.json"}
scene=$(cd "$(dirname "$scene")" && pwd)/$(basename "$scene")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
# spacing:duration: a second or more of wall time for each run.
sizes="0.0076:0.6 0.0055:0.3 0.0045:0.15 0.00381:0.1 0.0027:0.03 0.0019:0.015"
echo "round,spacing,particles,precision,threads,particle_steps_per_s"
for round in $(seq "$rounds"); do
    for size in $sizes; do
        spacing=${size%%:*}
        duration=${size##*:}
        for precision in single double; do
            log=$("$sphclip" run "$scene" --set solver.precision="$precision" \
                --set fluid.spacing="$spacing" --duration "$duration" --no-png --no-mp4 \
                --threads "$threads" --out "$work/out" 2>&1)
            particles=$(grep -o '[0-9]* particles' <<<"$log" | head -1 | cut -d' ' -f1)
            rate=$(grep -o '([0-9.e+]* particle-steps/s)' <<<"$log" | tr -d '()' | cut -d' ' -f1)
            echo "$round,$spacing,$particles,$precision,$threads,$rate"
        done
    done
done
