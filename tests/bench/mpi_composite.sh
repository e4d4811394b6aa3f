#!/usr/bin/env bash
# Rendering over MPI ranks, gather against depth compositing (docs/mpi.md,
# "Rendering over ranks"): runs sphclip_bench_composite on 2 ranks twice,
# with each rank bound to one core (Open MPI's default at 2 ranks) and
# unbound (--bind-to none: llvmpipe's threads of each rank may use every
# core), and writes one CSV: the program's header lines (machine, load,
# LP_NUM_THREADS, llvmpipe) and rows of each run, plus lscpu's model name and
# the load average before and after. No figure is asserted; exits 1 when a
# case's two frames differ, 77 (ctest: skipped) when mpirun cannot start two
# processes here.
#
#   tests/bench/mpi_composite.sh BENCH MPIRUN CSV [program options...]
#   tests/bench/mpi_composite.sh build/tests/sphclip_bench_composite mpirun \
#       tests/bench/results/mpi_composite.csv --backends egl,osmesa
#   tests/bench/mpi_composite.sh BENCH MPIRUN - --tiny     # CI: one small case
set -euo pipefail

bench=$(readlink -f "${1:?usage: mpi_composite.sh BENCH MPIRUN CSV [options]}")
mpirun=${2:?usage: mpi_composite.sh BENCH MPIRUN CSV [options]}
csv=${3:?usage: mpi_composite.sh BENCH MPIRUN CSV [options]}
shift 3
work=$(mktemp -d /tmp/sphclip-composite-bench.XXXXXX)
trap 'rm -rf "$work"' EXIT
if [ "$(id -u)" -eq 0 ]; then
    export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
fi
export OMPI_MCA_btl=self,vader OMPI_MCA_btl_vader_single_copy_mechanism=none
if ! "$mpirun" -np 2 true > "$work/probe.log" 2>&1; then
    echo "mpi_composite: skipped, mpirun cannot start two processes here:" >&2
    cat "$work/probe.log" >&2
    exit 77
fi

{
    echo "# tests/bench/mpi_composite.sh $(basename "$bench") $(basename "$mpirun") CSV $*"
    echo "# lscpu: $(lscpu | sed -n 's/^Model name: *//p' | head -1), $(nproc) CPUs"
    echo "# load average before (1, 5, 15 min): $(cut -d' ' -f1-3 /proc/loadavg)"
} > "$work/all.csv"
status=0
for binding in core none; do
    "$mpirun" -np 2 --bind-to "$binding" "$bench" --csv "$work/$binding.csv" "$@" \
        > "$work/$binding.log" 2>&1 || status=$?
    cat "$work/$binding.log"
    [ "$status" -eq 0 ] || { echo "mpi_composite: --bind-to $binding failed ($status)" >&2; exit 1; }
    echo "# --bind-to $binding:" >> "$work/all.csv"
    if [ "$binding" = core ]; then
        cat "$work/$binding.csv" >> "$work/all.csv"
    else
        grep -v '^backend,' "$work/$binding.csv" >> "$work/all.csv"
    fi
done
echo "# load average after (1, 5, 15 min): $(cut -d' ' -f1-3 /proc/loadavg)" >> "$work/all.csv"
if [ "$csv" != - ]; then
    cp "$work/all.csv" "$csv"
fi
