#!/usr/bin/env bash
# One simulation over MPI ranks (docs/mpi.md) against the same run in one
# process: for each scene in tests/mpi/scenes, `mpirun -np 1`, `-np 2` and
# `-np 3 --oversubscribe` must give the stats.csv of the plain run (every
# column but obstacle_pushes and wall_s, so every frame's state hash over all
# particles), the same particle exports byte for byte, and a run.json that
# records the ranks. Then: an MP4 from 2 ranks equal to the plain one (when
# OpenGL works), SIGINT to mpirun finalising the MP4 (run.json
# "interrupted"; mpirun itself exits 1), and single precision with
# reflecting walls refused on 2 ranks with exit 2, naming the key.
#
#   tests/mpi/check_mpi.sh build/sphclip MPIRUN [CASE]
#
# CASE: hashes:SCENE (a scene of tests/mpi/scenes), video, interrupt,
# refused, composite:SCENE:BACKEND (render.mpi_composite = depth: the PNGs
# and MP4 of 2 and 3 ranks equal the plain run's, byte for byte; egl or
# osmesa), or all (the default). Exits 77 (ctest:
# skipped) when mpirun cannot start two processes here.
set -euo pipefail

sphclip=$(readlink -f "${1:?usage: check_mpi.sh SPHCLIP MPIRUN [CASE]}")
mpirun=${2:?usage: check_mpi.sh SPHCLIP MPIRUN [CASE]}
case_name=${3:-all}
here=$(cd "$(dirname "$0")" && pwd)
work=$(mktemp -d /tmp/sphclip-mpi.XXXXXX)
trap 'rm -rf "$work"' EXIT

fail() {
    echo "mpi: FAILED: $*" >&2
    exit 1
}
# Open MPI refuses root unless told; a container's root is the usual case.
if [ "$(id -u)" -eq 0 ]; then
    export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
fi
# Shared memory between the ranks of one machine, no network probing.
export OMPI_MCA_btl=self,vader OMPI_MCA_btl_vader_single_copy_mechanism=none
export OMPI_MCA_rmaps_base_oversubscribe=1 OMPI_MCA_hwloc_base_binding_policy=none
# Open MPI's own allocations outlive MPI_Finalize (sanitizer build).
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=0}

mpi() { # ranks, then sphclip's arguments
    local ranks=$1
    shift
    timeout 120 "$mpirun" -np "$ranks" "$sphclip" "$@"
}

timeout 30 "$mpirun" -np 2 true > "$work/probe.log" 2>&1 || {
    cat "$work/probe.log"
    echo "mpi: SKIPPED: $mpirun cannot start 2 processes here"
    exit 77
}

# The stats.csv columns that must agree (all but obstacle_pushes, wall_s).
agreed() { cut -d, -f1-16,18 "$1"; }

check_hashes() { # a scene of tests/mpi/scenes, by name
    local name=$1
    local scene="$here/scenes/$name.json"
    [ -f "$scene" ] || fail "no scene $scene"
    {
        timeout 120 "$sphclip" run "$scene" --out "$work/$name-plain" --no-png --no-mp4 \
            --export csv --threads 1 --quiet > /dev/null ||
            fail "$name: the plain run failed"
        [ "$(wc -l < "$work/$name-plain/stats.csv")" -ge 3 ] || fail "$name: too few frames"
        for ranks in 1 2 3; do
            out="$work/$name-np$ranks"
            mpi "$ranks" run "$scene" --out "$out" --no-png --no-mp4 --export csv --threads 1 \
                --quiet > "$out.log" 2>&1 || {
                cat "$out.log"
                fail "$name: $ranks ranks: mpirun failed"
            }
            if ! diff <(agreed "$work/$name-plain/stats.csv") <(agreed "$out/stats.csv") \
                > "$out.diff"; then
                head -n 8 "$out.diff"
                fail "$name: $ranks ranks: stats.csv (state hashes) differ from the plain run"
            fi
            diff -r "$work/$name-plain/particles" "$out/particles" > /dev/null ||
                fail "$name: $ranks ranks: particle exports differ from the plain run"
            python3 - "$out/run.json" "$ranks" <<'PY' || fail "$name: $ranks ranks: run.json"
import json, sys
run = json.load(open(sys.argv[1]))
ranks = int(sys.argv[2])
assert run["status"] == "completed", run["status"]
assert run["mpi"]["ranks"] == ranks, run["mpi"]
if ranks > 1:
    mpi = run["mpi"]
    assert len(mpi["owned_and_halo_per_rank"]) == ranks, mpi
    assert mpi["steps"] > 0 and mpi["gather_bytes_received_per_step"] > 0, mpi
    # The halo's densities came from their owners (the halo exchange).
    assert mpi["halo_bytes_received_per_step"] > 0, mpi
    # Each rank held its own particles: together, every particle once.
    assert sum(mpi["owned_per_rank"]) == run["final_particles"], (mpi, run["final_particles"])
    # The whole state moved once a frame, not every step.
    assert mpi["frame_gathers"] == run["frames"], (mpi["frame_gathers"], run["frames"])
    assert any(s["name"] == "halo exchange" for s in run["stages"]), run["stages"]
    # No halo held every particle (a Verlet step after new particles
    # computes its accelerations first, over a halo of its own).
    assert mpi["whole_halos"] == 0, mpi
    print(f"{sys.argv[1]}: imbalance {mpi['imbalance']}, migrations {mpi['migrations']}, "
          f"most ranks one particle visited {mpi['most_ranks_visited']}")
PY
        done
        echo "mpi: $name: 1, 2 and 3 ranks give the plain run's state hashes and exports"
    }
    # What the scenes are there for: particles that changed rank, one that
    # crossed several ranks' ranges, a rank that owned nothing.
    python3 - "$work" "$name" <<'PY' || fail "$name no longer exercises migration"
import json, sys
w, name = sys.argv[1], sys.argv[2]
mpi = json.load(open(f"{w}/{name}-np3/run.json"))["mpi"]
if name == "jet_3d":
    assert mpi["migrations"] > 0, mpi
    assert mpi["migration_bytes_per_step"] > 0, mpi
    # The emitter filled the last rank: the ranges were cut again between
    # spatial sorts.
    assert mpi["rebalances"] > 0, mpi
    assert mpi["most_ranks_visited"] >= 3, mpi
    assert mpi["steps_with_an_empty_rank"] > 0, mpi
if name == "paddle_obstacle_2d":
    assert mpi["migrations"] > 0, mpi
if name.startswith("dfsph"):
    # Every iteration exchanged the halo's values and summed in particle order.
    assert mpi["sums_in_particle_order"] > 0, mpi
if name == "dfsph_2d":
    # Steps redone in halves: more steps over ranks than the run took.
    run = json.load(open(f"{w}/{name}-np3/run.json"))
    assert mpi["steps"] > run["steps"], (mpi["steps"], run["steps"])
    assert mpi["migrations"] > 0, mpi
if name == "dfsph_3d":
    assert mpi["migrations"] > 0, mpi
    assert mpi["steps_with_an_empty_rank"] > 0, mpi
PY
}

check_video() {
    scene="$here/scenes/paddle_obstacle_2d.json"
    timeout 120 "$sphclip" run "$scene" --out "$work/video-plain" --no-png --threads 1 --quiet \
        > "$work/video-plain.log" 2>&1 || {
        cat "$work/video-plain.log"
        echo "mpi: video: no OpenGL here; the MP4 is not checked"
        return 0
    }
    mpi 2 run "$scene" --out "$work/video-np2" --no-png --threads 1 --quiet \
        > "$work/video-np2.log" 2>&1 || {
        cat "$work/video-np2.log"
        fail "video: 2 ranks: mpirun failed"
    }
    cmp "$work/video-plain/clip.mp4" "$work/video-np2/clip.mp4" ||
        fail "video: the MP4 of 2 ranks differs from the plain run's"
    echo "mpi: video: 2 ranks write the plain run's MP4, byte for byte"
}

check_composite() { # scene, backend
    local name=$1 backend=$2
    local scene="$here/scenes/$name.json"
    [ -f "$scene" ] || fail "no scene $scene"
    # 3D: shadows (every rank's casters) and ambient occlusion (the
    # composited depth) on, at a size where some spheres are drawn on squares
    # and the smaller on triangles (the two groups' order).
    local look=()
    grep -q '"dimension": 3' "$scene" &&
        look=(--set render.shadows=true --set render.ambient_occlusion=true
            --set "render.size=[480,270]")
    local plain="$work/composite-$name-$backend-plain"
    timeout 120 "$sphclip" run "$scene" --out "$plain" --backend "$backend" --threads 1 \
        --quiet "${look[@]}" > "$plain.log" 2>&1 || {
        cat "$plain.log"
        echo "mpi: composite: no OpenGL ($backend) here; not checked"
        return 0
    }
    for ranks in 2 3; do
        out="$work/composite-$name-$backend-np$ranks"
        mpi "$ranks" run "$scene" --out "$out" --backend "$backend" --threads 1 --quiet \
            "${look[@]}" --set render.mpi_composite=depth > "$out.log" 2>&1 || {
            cat "$out.log"
            fail "composite: $name, $backend, $ranks ranks: mpirun failed"
        }
        for png in "$plain"/frames/*.png; do
            cmp -s "$png" "$out/frames/$(basename "$png")" ||
                fail "composite: $name, $backend, $ranks ranks: $(basename "$png") differs" \
                    "from the plain run's"
        done
        cmp -s "$plain/clip.mp4" "$out/clip.mp4" ||
            fail "composite: $name, $backend, $ranks ranks: the MP4 differs from the plain run's"
        python3 - "$out/run.json" "$plain/run.json" <<'PY' ||
import json, sys
run, plain = (json.load(open(p)) for p in sys.argv[1:3])
render = run["mpi"]["render"]
assert render["mpi_composite"] == "depth", render
assert render["frames_by_depth"] == run["frames"] > 0, (render, run["frames"])
assert any(s["name"] == "composite" for s in run["stages"]), run["stages"]
# The colour range's warnings count every rank's particles.
assert run.get("warnings") == plain.get("warnings"), (run.get("warnings"), plain.get("warnings"))
PY
            fail "composite: $name, $backend, $ranks ranks: run.json"
    done
    echo "mpi: composite: $name, $backend: 2 and 3 ranks composited by depth give the plain" \
        "run's PNGs and MP4, byte for byte"
}

check_interrupt() {
    scene="$here/scenes/paddle_obstacle_2d.json"
    out="$work/interrupted"
    # Long enough that SIGINT comes mid-run.
    timeout 120 "$mpirun" -np 2 "$sphclip" run "$scene" --out "$out" --no-png --threads 1 \
        --duration 30 --quiet > "$out.log" 2>&1 &
    pid=$!
    for _ in $(seq 600); do
        [ -f "$out/stats.csv" ] && [ "$(wc -l < "$out/stats.csv")" -ge 4 ] && break
        sleep 0.1
    done
    [ -f "$out/stats.csv" ] || {
        kill -KILL "$pid" 2> /dev/null || true
        cat "$out.log"
        fail "interrupt: the run never wrote stats.csv"
    }
    # mpirun's own pid, not timeout's.
    kill -INT "$(pgrep -P "$pid" -x mpirun || echo "$pid")"
    code=0
    wait "$pid" || code=$?
    grep -q '"status": "interrupted"' "$out/run.json" || {
        cat "$out.log"
        fail "interrupt: run.json does not say interrupted (exit $code)"
    }
    # Open MPI's mpirun turns SIGINT into SIGTERM to every rank (which stop
    # together, rank 0 finishing its outputs) and exits 1 itself.
    [ "$code" -ne 0 ] || fail "interrupt: mpirun exited 0"
    if [ -f "$out/clip.mp4" ]; then
        grep -q moov "$out/clip.mp4" || fail "interrupt: clip.mp4 has no index (not finalised)"
        echo "mpi: interrupt: SIGINT to mpirun ends both ranks as interrupted, clip.mp4 finalised"
    else
        grep -q "OpenGL\|GL context" "$out.log" || fail "interrupt: no clip.mp4"
        echo "mpi: interrupt: SIGINT to mpirun ends both ranks as interrupted (no OpenGL: no MP4)"
    fi
}

check_refused() {
    code=0
    mpi 2 run "$here/scenes/jet_3d.json" --out "$work/refused" --no-png --no-mp4 \
        --set solver.precision=single --set solver.walls=reflect --quiet \
        > "$work/refused.log" 2>&1 || code=$?
    [ "$code" -eq 2 ] || {
        cat "$work/refused.log"
        fail "refused: single precision with reflecting walls on 2 ranks exited $code, not 2"
    }
    grep -q "solver.walls: single precision over MPI ranks needs wall particles" \
        "$work/refused.log" || fail "refused: the message does not name solver.walls"
    [ ! -e "$work/refused/stats.csv" ] || fail "refused: wrote stats.csv"
    echo "mpi: refused: single precision with reflecting walls on 2 ranks exits 2 naming" \
        "solver.walls, writing nothing"
}

case "$case_name" in
hashes:*) check_hashes "${case_name#hashes:}" ;;
composite:*)
    spec=${case_name#composite:}
    check_composite "${spec%%:*}" "${spec#*:}"
    ;;
video) check_video ;;
interrupt) check_interrupt ;;
refused) check_refused ;;
all)
    for scene in "$here"/scenes/*.json; do
        check_hashes "$(basename "$scene" .json)"
    done
    check_video
    for backend in egl osmesa; do
        check_composite jet_3d "$backend"
        check_composite paddle_obstacle_2d "$backend"
    done
    check_interrupt
    check_refused
    ;;
*) fail "unknown case $case_name" ;;
esac
