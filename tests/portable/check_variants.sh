#!/usr/bin/env bash
# A portable build's instruction-set variants (docs/building.md, "One binary
# for every x86-64"), each run on a processor it is for. The host runs the
# widest it has; qemu-user's emulator (Debian's qemu-user) runs the same
# binary as a processor without AVX (-cpu Nehalem: x86-64-v2, the build's
# baseline) and as one with AVX2 and no AVX-512 (-cpu Haswell: x86-64-v3).
# For each processor:
#   - run.json names the variants the program chose: the single-precision
#     passes' (`machine.simd_variant`: baseline, avx2, avx512) and the
#     double-precision passes' clones (`machine.double_variant`: baseline,
#     x86-64-v3, x86-64-v4);
#   - three short runs (3D wcsph in double, 2D wcsph in single, 3D dfsph)
#     end as the host's do: each variant rounds differently (vector widths,
#     fused multiply-adds), so the runs are compared within a tolerance,
#     not bit for bit (the thread counts' bit-identity is checked within
#     one variant by the test suite);
#   - the test suite's single-precision cases, which run every variant the
#     processor has, pass.
#
#   tests/portable/check_variants.sh BUILD_DIR
#
# BUILD_DIR: a build configured with -DSPHCLIP_ARCH=x86-64-v2 (or any
# non-native value), with sphclip and sphclip_tests built. Exits 77 when
# qemu-x86_64 is missing or the build has no variants.
set -euo pipefail

build=$(readlink -f "${1:?usage: check_variants.sh BUILD_DIR}")
# The program proper, not its launcher (build/sphclip), which would start it
# outside the emulator.
sphclip=$build/libexec/sphclip/sphclip
tests=$build/sphclip_tests
repo=$(cd "$(dirname "$0")/../.." && pwd)
work=$(mktemp -d /tmp/sphclip-variants.XXXXXX)
# Started directly, the program sets libgomp's spin count by starting itself
# again (cli/wait_policy.cpp), which would leave the emulator: given here, it
# starts once.
export GOMP_SPINCOUNT=${GOMP_SPINCOUNT:-10000}
trap 'rm -rf "$work"' EXIT

fail() {
    echo "variants: FAILED: $*" >&2
    exit 1
}
variant_of() { # run.json key
    python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['machine'][sys.argv[2]])" "$1" "$2"
}
command -v qemu-x86_64 >/dev/null || {
    echo "variants: qemu-x86_64 not found (apt-get install qemu-user): skipped"
    exit 77
}
[[ -x $sphclip ]] || fail "no $sphclip"
"$sphclip" run "$repo/scenes/dam_break_water_2d.json" --set fluid.spacing=0.01 --duration 0.01 \
    --fps 100 --no-png --no-mp4 --quiet --out "$work/probe" || fail "the probe run"
if [[ $(variant_of "$work/probe/run.json" double_variant) == native ]]; then
    echo "variants: a native build has no variants: skipped"
    exit 77
fi

# name, runner, the variants it must choose ("" for the host: its widest).
processors=(
    "host||"
    "x86-64-v3|qemu-x86_64 -cpu Haswell|avx2 x86-64-v3"
    "x86-64-v2|qemu-x86_64 -cpu Nehalem|baseline baseline"
)
runs=(
    "dam3d|scenes/dam_break_water_3d.json|--set fluid.spacing=0.008 --set solver.precision=double"
    "dam2d|scenes/dam_break_water_2d.json|--set fluid.spacing=0.004 --set solver.precision=single"
    "dfsph3d|scenes/dam_break_water_3d_dfsph.json|--set fluid.spacing=0.008"
)


for p in "${processors[@]}"; do
    IFS='|' read -r name runner expected <<<"$p"
    for r in "${runs[@]}"; do
        IFS='|' read -r run scene options <<<"$r"
        out=$work/$name-$run
        # shellcheck disable=SC2086
        (cd "$repo" && $runner "$sphclip" run "$scene" $options --duration 0.02 --fps 100 \
            --threads 2 --no-png --no-mp4 --quiet --out "$out") ||
            fail "$name: $run did not complete"
    done
    single=$(variant_of "$work/$name-dam2d/run.json" simd_variant)
    double=$(variant_of "$work/$name-dam3d/run.json" double_variant)
    echo "variants: $name: single-precision passes $single, double-precision passes $double"
    if [[ -n $expected ]]; then
        [[ "$single $double" == "$expected" ]] || fail "$name chose $single $double, not $expected"
    fi
done

# Each run's last frame against the host's: the mean density and the
# kinetic energy within 1e-6 (relative), the same particle count.
for r in "${runs[@]}"; do
    IFS='|' read -r run _ _ <<<"$r"
    for p in "${processors[@]:1}"; do
        IFS='|' read -r name _ _ <<<"$p"
        python3 - "$work/host-$run/stats.csv" "$work/$name-$run/stats.csv" "$name" "$run" <<'PY' ||
import csv, sys
host = list(csv.DictReader(open(sys.argv[1])))[-1]
other = list(csv.DictReader(open(sys.argv[2])))[-1]
assert host["particles"] == other["particles"], "particle counts differ"
for key in ("density_avg", "kinetic_energy"):
    a, b = float(host[key]), float(other[key])
    scale = max(abs(a), abs(b), 1e-300)
    if abs(a - b) / scale > 1e-6:
        sys.exit(f"{key}: host {a!r}, {sys.argv[3]} {b!r}")
print(f"variants: {sys.argv[4]}: {sys.argv[3]} agrees with the host "
      f"(density_avg {other['density_avg']}, kinetic_energy {other['kinetic_energy']})")
PY
            fail "$run on $name differs from the host's"
    done
done

# The single-precision test cases on each emulated processor.
if [[ -x $tests ]]; then
    for p in "${processors[@]:1}"; do
        IFS='|' read -r name runner _ <<<"$p"
        # shellcheck disable=SC2086
        (cd "$repo" && $runner "$tests" "[single]" >"$work/tests-$name.log" 2>&1) ||
            { tail -30 "$work/tests-$name.log"; fail "the [single] tests on $name"; }
        echo "variants: the [single] tests pass on $name: $(grep -E 'All tests passed' "$work/tests-$name.log")"
    done
fi
echo "variants: all checks passed"
