#!/usr/bin/env bash
# What limits the number of runs in a plan (docs/cluster.md, "How many
# runs"): writes a study plan of N runs with --dry-run (--engine slurm, so
# the scripts too), counts its files, gives every run the outputs of one
# real tiny run as synthetic results, and times `sphclip collect`.
#
#   tests/bench/plan_scale.sh build/sphclip [N=1000]
#
# Prints seconds and file counts; a program for a figure, not a test.
set -euo pipefail
sphclip=$(readlink -f "${1:?usage: plan_scale.sh SPHCLIP [N]}")
runs=${2:-1000}
work=$(mktemp -d /tmp/sphclip-plan-scale.XXXXXX)
trap 'rm -rf "$work"' EXIT
cd "$work"
cat > tiny.json << 'SCENE'
{
    "domain": {"min": [0, 0], "max": [0.1, 0.1]},
    "fluid": {"spacing": 0.005, "blocks": [{"min": [0, 0], "max": [0.03, 0.03]}]},
    "duration": 0.1,
    "fps": 40
}
SCENE
now() { date +%s.%N; }
seconds() { awk "BEGIN { printf \"%.2f\", $(now) - $1 }"; }
# N distinct values of one key: N runs.
values=$(awk -v n="$runs" 'BEGIN { for (i = 0; i < n; ++i) printf "%s%.6g", (i ? "," : ""), 1e-4 + i * 1e-8 }')
start=$(now)
"$sphclip" study tiny.json --vary "solver.dt=$values" --metric kinetic_energy --reference finest \
    --engine slurm --dry-run --out plan > plan.log
echo "plan of $runs runs written in $(seconds "$start") s: $(find plan -type f | wc -l) files," \
    "$(du -sh plan | cut -f1)"

# One real run, its outputs copied into every run's folder as its result.
"$sphclip" plan-task plan 0 > /dev/null
first=$(ls -d plan/runs/*/ | head -n 1)
python3 -c 'import json; [print(r["request"]["out"]) for r in json.load(open("plan/plan.json"))["runs"]]' |
    while read -r run; do
        [ -d "$run" ] && continue
        mkdir -p "$run"
        cp "$first/run.json" "$first/stats.csv" "$first/run.log" "$run"
    done
record="plan/plan/$(ls plan/plan | head -n 1)/exit.json"
for task in plan/plan/*/; do
    [ -f "$task/exit.json" ] || cp "$record" "$task"
done
echo "with synthetic results: $(find plan -type f | wc -l) files, $(du -sh plan | cut -f1)"
start=$(now)
"$sphclip" collect plan > collect.log
echo "collect of $runs runs: $(seconds "$start") s ($(grep -c ',ok,' plan/study.csv) rows ok)"
