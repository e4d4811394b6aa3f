#!/usr/bin/env bash
# Prints a fingerprint of what sphclip makes from every shipped scene (and a
# few render and solver variants): the MD5 of each PNG frame, each frame's
# state hash from stats.csv, and run.json's resolved scene. Two builds that
# print the same fingerprint behave the same on these scenes; a refactoring
# that must keep behaviour (frames byte-identical, state hashes identical,
# the scene round trip) is checked with
#   tests/behaviour/fingerprint.sh OLD/sphclip > old.txt
#   tests/behaviour/fingerprint.sh NEW/sphclip > new.txt && diff old.txt new.txt
# Runs take 3 frames each at 2 threads (about a minute in all).
set -euo pipefail
exe="$(realpath "${1:?usage: fingerprint.sh PATH/TO/sphclip}")"
cd "$(dirname "$0")/../.."
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

run() { # label scene [args...]
    local label="$1" scene="$2"
    shift 2
    local out="$work/$label"
    local status=0
    "$exe" run "$scene" --out "$out" --quiet --no-mp4 --threads 2 --fps 30 --duration 0.1 "$@" \
        >/dev/null 2>"$work/stderr" || status=$?
    echo "== $label exit $status"
    if [ "$status" -ne 0 ]; then
        sed 's/^/   /' "$work/stderr"
        return
    fi
    (cd "$out/frames" && md5sum ./*.png)
    # state_hash, by its column's name.
    awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) if ($i == "state_hash") c = i; next }
             { print "state", $1, $c }' "$out/stats.csv"
    python3 -c 'import json, sys; print("scene", json.dumps(json.load(open(sys.argv[1]))["scene"], sort_keys=True))' \
        "$out/run.json"
}

for scene in scenes/*.json; do
    run "$(basename "$scene" .json)" "$scene"
done
run default-builtin ""
run dam2d-wcsph scenes/dam_break_2d.json --set solver.name=wcsph
run dam2d-wcsph-double scenes/dam_break_2d.json --set solver.name=wcsph --set solver.precision=double
run dam2d-dfsph scenes/dam_break_2d.json --set solver.name=dfsph --set render.colour=pressure
run dam2d-density scenes/dam_break_2d.json --set render.colour=density --set render.size=[640,360]
run dam3d-mesh scenes/dam_break_3d.json --set render.spheres=mesh --set render.size=[640,360]
run dam3d-camera scenes/dam_break_3d.json --set render.camera.position=[0.6,0.4,0.5] \
    --set render.camera.target=[0.2,0.05,0.05] --set render.colour=density
run dam3d-wcsph scenes/dam_break_3d.json --set solver.name=wcsph --set render.cull_buried=false
run emitter-xsph scenes/emitter_fill_2d.json --set effects.xsph.epsilon=0.3
run drop-osmesa scenes/zero_gravity_drop_3d.json --backend osmesa
