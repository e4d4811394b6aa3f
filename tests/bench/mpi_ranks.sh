#!/usr/bin/env bash
# One rank of 2 threads against 2 ranks of 1 thread (docs/mpi.md): the same
# scene run plainly with --threads 2 and under `mpirun -np 2 ... --threads 1`,
# each REPEAT times (default 3); prints, per layout, the median wall time of
# the run and the simulation's particle-steps per second, and for the ranks
# the halo (particles each rank steps besides its own), the bytes each rank
# receives per step (halo exchange, gather) and the measured imbalance, from
# run.json, and rank 0's stage table (where a rank's time goes; for dfsph
# also the time its solves spent in their per-iteration exchanges and sums). Also checks
# that the two layouts' state hashes agree. No figure is asserted.
#
#   tests/bench/mpi_ranks.sh build/sphclip [SCENE] [DURATION] [REPEAT]
#
# Default scene: scenes/dam_break_water_3d.json (wcsph, 11,700 particles) for 0.05 s,
# run with --no-png --no-mp4 so that only the simulation is timed.
set -euo pipefail

sphclip=$(readlink -f "${1:?usage: mpi_ranks.sh SPHCLIP [SCENE] [DURATION] [REPEAT]}")
root=$(cd "$(dirname "$0")/../.." && pwd)
scene=${2:-$root/scenes/dam_break_water_3d.json}
duration=${3:-0.05}
repeat=${4:-3}
mpirun=${MPIRUN:-mpirun}
work=$(mktemp -d /tmp/sphclip-mpi-bench.XXXXXX)
trap 'rm -rf "$work"' EXIT
if [ "$(id -u)" -eq 0 ]; then
    export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
fi
export OMPI_MCA_btl=self,vader OMPI_MCA_btl_vader_single_copy_mechanism=none

run_layout() { # name, threads per rank, then the command up to sphclip's arguments
    local name=$1 threads=$2
    shift 2
    for k in $(seq "$repeat"); do
        "$@" run "$scene" --out "$work/$name-$k" --duration "$duration" --no-png --no-mp4 \
            --threads "$threads" --quiet > "$work/$name-$k.log" 2>&1 || {
            cat "$work/$name-$k.log"
            exit 1
        }
    done
}

run_layout plain 2 timeout 900 "$sphclip"
run_layout ranks 1 timeout 900 "$mpirun" -np 2 --bind-to core "$sphclip"

python3 - "$work" "$repeat" "$scene" <<'PY'
import json, statistics, sys
work, repeat, scene = sys.argv[1], int(sys.argv[2]), sys.argv[3]
def runs(name):
    return [json.load(open(f"{work}/{name}-{k}/run.json")) for k in range(1, repeat + 1)]
def hashes(name):
    rows = open(f"{work}/{name}-1/stats.csv").read().splitlines()
    return [r.split(",")[17] for r in rows[1:]]
plain, ranks = runs("plain"), runs("ranks")
print(f"scene {scene}, {plain[0]['final_particles']} particles, {plain[0]['steps']} steps, "
      f"median of {repeat}")
for name, rs in (("1 rank x 2 threads", plain), ("2 ranks x 1 thread", ranks)):
    wall = statistics.median(r["wall_s"] for r in rs)
    rate = statistics.median(r["steps"] * r["final_particles"] / r["wall_s"] for r in rs)
    print(f"{name}: {wall:.3f} s, {rate:.3g} particle-steps/s (final count)")
m = ranks[0]["mpi"]
print(f"ranks: owned {m['owned_per_rank']}, owned + halo {m['owned_and_halo_per_rank']}, "
      f"halo {m['halo_particles_per_step']:.0f} particles per rank-step, "
      f"halo exchange {m['halo_bytes_received_per_step']:.0f} and "
      f"gather {m['gather_bytes_received_per_step']:.0f} bytes received per rank-step, "
      f"migration {m['migration_bytes_per_step']} bytes per step")
print(f"imbalance (max / mean): particles {m['imbalance']['particles_mean']:.3f} "
      f"(worst {m['imbalance']['particles_max']:.3f}), solver seconds "
      f"{m['imbalance']['seconds_mean']:.3f} (worst {m['imbalance']['seconds_max']:.3f})")
if m.get("sums_in_particle_order", 0) > 0:
    # dfsph: its iterations' halo exchanges and sums across the ranks, inside its solve stages.
    print(f"solve exchanges and sums in particle order (within the solve stages, rank 0): "
          f"{m['solve_exchange_seconds']:.2f} s, {m['sums_in_particle_order'] / m['steps']:.1f} "
          f"sums per rank-step")
for name, r in (("1 rank x 2 threads", plain[0]), ("2 ranks x 1 thread, rank 0", ranks[0])):
    print(f"{name}: " + ", ".join(f"{st['name']} {st['seconds']:.2f} s"
                                  for st in r["stages"] if st.get("seconds", 0) > 0.005))
same = hashes("plain") == hashes("ranks")
print(f"state hashes of the two layouts: {'identical' if same else 'DIFFERENT'}")
sys.exit(0 if same else 1)
PY
