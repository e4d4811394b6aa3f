#!/usr/bin/env bash
# The Slurm engine against a real Slurm: starts munged, slurmctld and slurmd
# on localhost (Debian's slurm-wlm and munge, a generated slurm.conf with
# this machine's cores and memory, everything in a temporary folder), runs a
# 4-run study and a batch with --engine slurm, waits for their collect jobs,
# and checks the results against the same plans run with --engine local:
# identical state hashes per run, identical tables but for wall times (and the
# Pareto front, which weighs them). A
# failed batch run is sent again with `collect --resubmit` (a new array of
# that run alone). The daemons are stopped on exit.
#
#   tests/slurm/check_slurm.sh build/sphclip
#
# Exits 77 (ctest: skipped) with the reason where the daemons cannot start:
# not root, or slurm-wlm or munge not installed (.ci/setup --tests installs
# them). Prints the seconds from submission to collected results, for
# docs/cluster.md; nothing here is timed against a limit but the wait.
set -euo pipefail

sphclip=$(readlink -f "${1:?usage: check_slurm.sh SPHCLIP}")
skip() {
    echo "slurm_engine: SKIPPED: $*"
    exit 77
}
fail() {
    echo "slurm_engine: FAILED: $*" >&2
    for log in "$work"/log/*.log "$work"/munge/munged.log; do
        [ -f "$log" ] && { echo "--- $log" >&2; tail -n 15 "$log" >&2; }
    done
    exit 1
}

[ "$(id -u)" -eq 0 ] || skip "not root: slurmd runs jobs as their user and must start as root"
for program in munged munge slurmctld slurmd sbatch scontrol sinfo; do
    command -v "$program" > /dev/null ||
        skip "$program not found (.ci/setup --tests installs slurm-wlm and munge)"
done

work=$(mktemp -d /tmp/sphclip-slurm.XXXXXX)
stop_daemons() {
    for pidfile in "$work/slurmd.pid" "$work/slurmctld.pid" "$work/munge/munged.pid"; do
        [ -s "$pidfile" ] && kill "$(cat "$pidfile")" 2> /dev/null || true
    done
    for pidfile in "$work/slurmd.pid" "$work/slurmctld.pid" "$work/munge/munged.pid"; do
        for _ in $(seq 20); do
            [ -s "$pidfile" ] && kill -0 "$(cat "$pidfile")" 2> /dev/null || break
            sleep 0.25
        done
    done
    rm -rf "$work"
}
trap stop_daemons EXIT
# munged refuses a socket folder others cannot enter, and a key others can read.
chmod 755 "$work"
mkdir -p "$work/munge" "$work/state" "$work/spool" "$work/log"
chmod 755 "$work/munge"
head -c 1024 /dev/urandom > "$work/munge/munge.key"
chmod 400 "$work/munge/munge.key"
socket="$work/munge/munge.socket"
munged --force --socket="$socket" --key-file="$work/munge/munge.key" \
    --log-file="$work/munge/munged.log" --pid-file="$work/munge/munged.pid" \
    --seed-file="$work/munge/munged.seed" ||
    skip "munged does not start: $(tail -n 2 "$work/munge/munged.log" 2> /dev/null)"
munge -n -S "$socket" | unmunge -S "$socket" > /dev/null || skip "munge cannot encode a credential"

# Ports of their own, so that a site's Slurm on this machine is not touched.
port=$((20000 + ($$ % 10000) * 2))
cpus=$(nproc)
memory=$(awk '/MemTotal/ { print int($2 / 1024 * 0.9) }' /proc/meminfo)
cat > "$work/slurm.conf" << CONF
ClusterName=sphclip-test
SlurmctldHost=localhost
SlurmctldPort=$port
SlurmdPort=$((port + 1))
SlurmUser=root
AuthType=auth/munge
AuthInfo=socket=$socket
CredType=cred/munge
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/log/slurmctld.log
SlurmdLogFile=$work/log/slurmd.log
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
MpiDefault=none
ReturnToService=2
SchedulerParameters=sched_interval=1
MinJobAge=600
NodeName=localhost NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=$memory State=UNKNOWN
PartitionName=test Nodes=localhost Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF="$work/slurm.conf"
slurmctld -f "$SLURM_CONF" || skip "slurmctld does not start: $(tail -n 2 "$work/log/slurmctld.log")"
slurmd -f "$SLURM_CONF" -N localhost || skip "slurmd does not start: $(tail -n 2 "$work/log/slurmd.log")"
for _ in $(seq 60); do
    [ "$(sinfo -h -o %T 2> /dev/null)" = "idle" ] && break
    sleep 0.5
done
[ "$(sinfo -h -o %T 2> /dev/null)" = "idle" ] || skip "the node does not come up: $(sinfo 2>&1 | tail -n 1)"
echo "slurm_engine: Slurm $(sinfo -V | cut -d' ' -f2) up on localhost ($cpus CPUs, $memory MB)"

# Waits until Slurm says job $1 has ended (3 minutes at most).
wait_job() {
    local state
    for _ in $(seq 360); do
        state=$(scontrol -o show job "$1" 2> /dev/null | grep -o 'JobState=[A-Z_]*' | head -n 1)
        case "$state" in
        JobState=COMPLETED | JobState=FAILED | JobState=CANCELLED | JobState=TIMEOUT | \
            JobState=NODE_FAIL | JobState=OUT_OF_MEMORY) return 0 ;;
        esac
        sleep 0.5
    done
    fail "job $1 did not end: $(scontrol -o show job "$1" 2>&1)"
}
# The collect job of the last submission of plan $1.
collect_job() {
    python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))[-1]["collect_job"])' \
        "$1/slurm/submissions.json"
}
# Each run's last state hash, "folder hash" a line.
hashes() {
    for run in "$1"/runs/*/; do
        printf '%s ' "$(basename "$run")"
        awk -F, '/^#/ { next } !c { for (i = 1; i <= NF; ++i) if ($i == "state_hash") c = i; next }
                 { h = $c } END { print h }' "$run/stats.csv"
    done
}
# A CSV table without the columns that depend on wall time (wall_s, and
# the Pareto front of error against it).
without_wall() {
    python3 -c 'import csv,sys
rows = list(csv.reader(open(sys.argv[1])))
keep = [i for i, name in enumerate(rows[0]) if name not in ("wall_s", "pareto")]
for row in rows: print([row[i] for i in keep])' "$1"
}
now() { date +%s.%N; }

cd "$work"
cat > tiny.json << 'SCENE'
{
    "domain": {"min": [0, 0], "max": [0.1, 0.1]},
    "fluid": {"spacing": 0.005, "blocks": [{"min": [0, 0], "max": [0.03, 0.03]}]},
    "duration": 0.1,
    "fps": 40
}
SCENE
sed 's/"fps": 40/"fps": 40, "effects": {"gravity": [0, -1e20]}/' tiny.json > blows_up.json
study=(study tiny.json --vary solver.dt=1e-4,2e-4 --vary fluid.spacing=0.005,0.004
    --metric kinetic_energy --threads 1)

# The study: Slurm, then the same plan locally.
start=$(now)
"$sphclip" "${study[@]}" --engine slurm --max-running 2 --out slurm_study > submit.log 2>&1 ||
    fail "study --engine slurm: $(cat submit.log)"
wait_job "$(collect_job slurm_study)"
[ -f slurm_study/study.png ] || fail "no study.png from the collect job: $(cat slurm_study/slurm/collect-*.out)"
slurm_s=$(awk "BEGIN { print $(now) - $start }")
start=$(now)
"$sphclip" "${study[@]}" --out local_study > local.log 2>&1 || fail "study --engine local: $(cat local.log)"
local_s=$(awk "BEGIN { print $(now) - $start }")
[ "$(hashes slurm_study | wc -l)" -eq 4 ] || fail "not 4 runs: $(hashes slurm_study)"
diff <(hashes local_study) <(hashes slurm_study) || fail "state hashes differ between engines"
diff <(without_wall local_study/study.csv) <(without_wall slurm_study/study.csv) ||
    fail "study.csv differs between engines"
grep -q 'ok' slurm_study/study.csv || fail "no run ok in $(cat slurm_study/study.csv)"
printf 'slurm_engine: 4-run study, submission to study.png: slurm %.1f s, local %.1f s\n' \
    "$slurm_s" "$local_s"

# The batch: clips of two scenes and one that blows up (exit 3), which
# collect --resubmit sends again as an array of that run alone.
batch=(batch tiny.json blows_up.json tiny.json --threads 1)
"$sphclip" "${batch[@]}" --engine slurm --out slurm_batch > submit.log 2>&1 ||
    fail "batch --engine slurm: $(cat submit.log)"
wait_job "$(collect_job slurm_batch)"
grep -q 'run 1 (01_blows_up): exit 3 (unstable)' slurm_batch/slurm/collect-*.out ||
    fail "the collect job does not report the unstable run: $(cat slurm_batch/slurm/collect-*.out)"
[ -s slurm_batch/runs/00_tiny/clip.mp4 ] || fail "no clip from the array task: $(ls slurm_batch/runs/00_tiny)"
"$sphclip" "${batch[@]}" --out local_batch > local.log 2>&1 && fail "the local batch did not exit 3"
diff <(without_wall local_batch/batch.csv) <(without_wall slurm_batch/batch.csv) ||
    fail "batch.csv differs between engines"
"$sphclip" collect --resubmit slurm_batch > resubmit.log 2>&1 || fail "resubmit: $(cat resubmit.log)"
grep -q -- '--array=1$' slurm_batch/slurm/array.sbatch || fail "resubmitted $(grep array= slurm_batch/slurm/array.sbatch)"
wait_job "$(collect_job slurm_batch)"
python3 -c 'import json,sys; s = json.load(open(sys.argv[1])); assert [x["indices"] for x in s] == [[0, 1, 2], [1]], s' \
    slurm_batch/slurm/submissions.json || fail "submissions: $(cat slurm_batch/slurm/submissions.json)"
echo "slurm_engine: study and batch through Slurm match --engine local"
