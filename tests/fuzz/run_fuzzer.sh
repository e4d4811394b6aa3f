#!/usr/bin/env bash
# Fuzzes one of sphclip's readers for SECONDS (default 60) with libFuzzer,
# ASan and UBSan: tests/fuzz/run_fuzzer.sh [scene|obj|png] [SECONDS]
#   scene: the scene parser (src/scene/scene.cpp), the default
#   obj:   the OBJ mesh reader (src/scene/obj_mesh.cpp)
#   png:   the PNG reader of `sphclip compare` (src/output/png_io.cpp)
#
# Needs clang-14 and libFuzzer's runtime, Debian's libclang-rt-14-dev
# (apt-get install clang-14 libclang-rt-14-dev); not part of .ci/setup, as CI
# does not fuzz. Builds only the fuzzer, in build-fuzz/ (JOBS=N for parallel
# compiles, default 1). The corpus grows in build-fuzz/corpus/TARGET/ from run
# to run, seeded with the committed corpus tests/fuzz/corpus/TARGET/ (for
# scenes: scenes/*.json and tests/fuzz/regressions/). KEEP_CORPUS=1 copies the
# grown corpus, minimised, back into tests/fuzz/corpus/TARGET/. Any crash,
# leak, timeout or out-of-memory input is copied into
# tests/fuzz/regressions/ (scenes) or tests/fuzz/regressions/TARGET/, where
# the normal test suite reads it (tests/test_fuzz_regressions.cpp); the
# script then exits non-zero.
set -euo pipefail
cd "$(dirname "$0")/../.."

target=scene
if [[ "${1:-}" =~ ^(scene|obj|png)$ ]]; then
    target="$1"
    shift
fi
seconds="${1:-60}"
jobs="${JOBS:-1}"
build="build-fuzz"
fuzz=tests/fuzz

for tool in clang clang++; do
    command -v "$tool" >/dev/null || {
        echo "run_fuzzer: $tool not found (apt-get install clang-14 libclang-rt-14-dev)" >&2
        exit 2
    }
done

mkdir -p "$build"
CC=clang CXX=clang++ cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DSPHCLIP_FUZZ=ON -DSPHCLIP_BUILD_TESTS=OFF -DSPHCLIP_WERROR=OFF >"$build/configure.log" ||
    { cat "$build/configure.log" >&2; exit 2; }
cmake --build "$build" --target "sphclip_${target}_fuzzer" -j"$jobs"

corpus="$build/corpus/$target"
artifacts="$build/artifacts/$target/"
mkdir -p "$corpus" "$artifacts"
case "$target" in
scene)
    cp scenes/*.json "$corpus/"
    find "$fuzz/regressions" -maxdepth 1 -type f -exec cp {} "$corpus/" \;
    kept="$fuzz/regressions"
    # max_len: four times the largest shipped scene, room for deep nesting
    # and long keys.
    options=(-dict="$fuzz/scene.dict" -max_len=4096)
    ;;
obj)
    cp scenes/meshes/*.obj "$corpus/"
    kept="$fuzz/regressions/obj"
    options=(-dict="$fuzz/obj.dict" -max_len=8192)
    ;;
png)
    cp tests/golden/*.png "$corpus/"
    kept="$fuzz/regressions/png"
    options=(-dict="$fuzz/png.dict" -max_len=65536)
    ;;
esac
[ -d "$fuzz/corpus/$target" ] && cp "$fuzz/corpus/$target"/* "$corpus/" 2>/dev/null || true
[ -d "$kept" ] && find "$kept" -maxdepth 1 -type f -exec cp {} "$corpus/" \;

# An input that takes over 10 s or 2 GiB is a finding.
status=0
"$build/sphclip_${target}_fuzzer" "$corpus" "${options[@]}" \
    -max_total_time="$seconds" -rss_limit_mb=2048 -timeout=10 \
    -artifact_prefix="$artifacts" -print_final_stats=1 || status=$?

found=0
mkdir -p "$kept"
for input in "$artifacts"{crash,leak,timeout,oom,slow-unit}-*; do
    [ -e "$input" ] || continue
    cp "$input" "$kept/"
    echo "run_fuzzer: kept $kept/$(basename "$input")"
    found=1
done
rm -f "$artifacts"*
if [ "${KEEP_CORPUS:-0}" = 1 ] && [ "$target" != scene ]; then
    rm -rf "$fuzz/corpus/$target.new" && mkdir -p "$fuzz/corpus/$target.new"
    "$build/sphclip_${target}_fuzzer" -merge=1 "$fuzz/corpus/$target.new" "$corpus" \
        "${options[@]}" >/dev/null 2>&1
    rm -rf "$fuzz/corpus/$target" && mv "$fuzz/corpus/$target.new" "$fuzz/corpus/$target"
    echo "run_fuzzer: $(ls "$fuzz/corpus/$target" | wc -l) inputs kept in $fuzz/corpus/$target"
fi
if [ "$status" -ne 0 ] || [ "$found" -ne 0 ]; then
    echo "run_fuzzer: finding(s) above; fix the reader, then rerun" >&2
    exit 1
fi
echo "run_fuzzer: no finding in $seconds s"
