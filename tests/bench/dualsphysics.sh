#!/usr/bin/env bash
# sphclip against DualSPHysics (CPU) on DualSPHysics's own 2D validation dam
# break (issue 22, item 3; docs/benchmarks.md, "Against DualSPHysics"): both
# from rest to the same simulated time, interleaved over ROUNDS rounds with
# THREADS OpenMP threads each. Prints each run's wall seconds (the whole
# process; DualSPHysics's case made by GenCase beforehand, untimed), its
# steps and its fluid particle-steps per second.
#
#   tests/bench/dualsphysics.sh SPHCLIP DUALSPHYSICS GENCASE CASE_XML [DP] [STOP_AT] [ROUNDS] [THREADS] [SCENE] [SET]
#
# DUALSPHYSICS is a CPU build of DualSPHysics and GENCASE its case generator
# of the same version, both built or taken in a scratch folder outside this
# repository (docs/benchmarks.md says which and how). CASE_XML is
# DualSPHysics's examples/main/01_DamBreak/CaseDambreakVal2D_Def.xml; a copy
# is edited here: its spacing dp (0.02 m: 5,000 fluid particles; 0.01:
# 20,000), TimeMax, TimeOut 0.1 s, its gauges left out (sphclip measures
# none), and the keys DtFixed and DtFixedFile left out (DualSPHysics 5.0
# reads DtFixed as a file's name). sphclip runs
# tests/bench/peers/dualsphysics_dambreak_val2d.json at the same dp, or
# SCENE: tests/bench/peers/dualsphysics_dambreak_3d.json for DualSPHysics's
# 3D dam break (examples/main/01_DamBreak/CaseDambreak_Def.xml, edited the
# same way; dp 0.0093 m: about 99,000 fluid particles; issue 22, item 5),
# with SET (e.g. solver.precision=single) passed to sphclip's --set.
set -euo pipefail
sphclip=${1:?usage: dualsphysics.sh SPHCLIP DUALSPHYSICS GENCASE CASE_XML [DP] [STOP_AT] [ROUNDS] [THREADS]}
dualsphysics=${2:?DUALSPHYSICS}
gencase=${3:?GENCASE}
case_xml=${4:?CASE_XML}
dp=${5:-0.02}
stop_at=${6:-1.0}
rounds=${7:-3}
threads=${8:-2}
here=$(cd "$(dirname "$0")" && pwd)
ours=${9:-"$here/peers/dualsphysics_dambreak_val2d.json"}
set_option=()
[ -n "${10:-}" ] && set_option=(--set "${10}")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

python3 - "$case_xml" "$work/Case_Def.xml" "$dp" "$stop_at" <<'PY'
import sys
import xml.etree.ElementTree as ET
source, target, dp, stop_at = sys.argv[1:]
tree = ET.parse(source)
root = tree.getroot()
root.find("casedef/geometry/definition").set("dp", dp)
execution = root.find("execution")
special = execution.find("special")
if special is not None:
    execution.remove(special)
parameters = execution.find("parameters")
for p in list(parameters.findall("parameter")):
    key = p.get("key")
    if key in ("DtFixed", "DtFixedFile"):
        parameters.remove(p)
    elif key == "TimeMax":
        p.set("value", stop_at)
    elif key == "TimeOut":
        p.set("value", "0.1")
tree.write(target, encoding="UTF-8", xml_declaration=True)
PY
(cd "$work" && "$gencase" Case_Def case/Case -save:all > gencase.log 2>&1) ||
    { cat "$work/gencase.log"; exit 1; }

# A failed run stops the script with the end of its log, not a time.
ran() {
    local log=$1
    shift
    "$@" > "$log" 2>&1 || { echo "dualsphysics.sh: failed: $*" >&2; tail -20 "$log" >&2; return 1; }
}
peer() {
    rm -rf "$work/peer"
    OMP_NUM_THREADS=$threads ran "$work/peer.log" "$dualsphysics" "$work/case/Case" "$work/peer" \
        -cpu -ompthreads:"$threads" -svres:1
}
mine() {
    ran "$work/ours.log" "$sphclip" run "$ours" --set fluid.spacing="$dp" "${set_option[@]}" \
        --threads "$threads" --duration "$stop_at" --no-png --no-mp4 --out "$work/ours"
}
seconds() {
    local t0 t1
    t0=$(date +%s.%N)
    "$@" || return 1
    t1=$(date +%s.%N)
    echo "$t1 - $t0" | bc
}

echo "# $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//'), $(nproc) CPUs, load $(cut -d' ' -f1-3 /proc/loadavg); $threads threads; $(basename "$case_xml") against $(basename "$ours")${10:+ --set ${10}}; dp $dp m; to t = $stop_at s"
echo "round,DualSPHysics_s,sphclip_s,DualSPHysics_steps,sphclip_steps,DualSPHysics_fluid_particles,sphclip_fluid_particles,DualSPHysics_M_fluid_particle_steps_per_s,sphclip_M_fluid_particle_steps_per_s"
for round in $(seq 1 "$rounds"); do
    p=$(seconds peer) || exit 1
    o=$(seconds mine) || exit 1
    # DualSPHysics's Run.csv: Np;...;Steps (10th);...;Nbound (22nd).
    read -r peer_steps peer_fluid < <(awk -F';' 'NR == 2 { print $10, $4 - $22 }' "$work/peer/Run.csv")
    # stats.csv: frame,time,steps,dt,particles,... sphclip stops at its last
    # whole frame (the scene's 10 fps), so a STOP_AT between frames would
    # compare unequal times: refused.
    IFS=, read -r _ reached steps _ fluid _ < <(tail -1 "$work/ours/stats.csv")
    if [ "$(echo "$reached - $stop_at < -0.000001" | bc)" = 1 ]; then
        echo "dualsphysics.sh: sphclip stopped at t = $reached s, its last frame before $stop_at s: give STOP_AT as a multiple of 0.1 s" >&2
        exit 1
    fi
    echo "$round,$p,$o,$peer_steps,$steps,$peer_fluid,$fluid,$(echo "scale=3; $peer_steps * $peer_fluid / $p / 1000000" | bc),$(echo "scale=3; $steps * $fluid / $o / 1000000" | bc)"
done
echo "# load at the end $(cut -d' ' -f1-3 /proc/loadavg)"
