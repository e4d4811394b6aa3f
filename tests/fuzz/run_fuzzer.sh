#!/usr/bin/env bash
# Fuzzes the scene parser for SECONDS (default 60) with libFuzzer, ASan and
# UBSan: tests/fuzz/run_fuzzer.sh [SECONDS]
#
# Needs clang-14 and libFuzzer's runtime, Debian's libclang-rt-14-dev
# (apt-get install clang-14 libclang-rt-14-dev); not part of .ci/setup, as CI
# does not fuzz. Builds only the fuzzer, in build-fuzz/ (JOBS=N for parallel
# compiles, default 1). The corpus grows in build-fuzz/corpus/ from run to
# run, seeded with scenes/*.json and tests/fuzz/regressions/. Any crash, leak,
# timeout or out-of-memory input is copied into tests/fuzz/regressions/, where
# the normal test suite parses it (tests/test_fuzz_regressions.cpp); the
# script then exits non-zero.
set -euo pipefail
cd "$(dirname "$0")/../.."

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
cmake --build "$build" --target sphclip_scene_fuzzer -j"$jobs"

corpus="$build/corpus/scene"
artifacts="$build/artifacts/"
mkdir -p "$corpus" "$artifacts"
cp scenes/*.json "$corpus/"
find "$fuzz/regressions" -type f -exec cp {} "$corpus/" \;

# max_len: four times the largest shipped scene, room for deep nesting and
# long keys. A scene that takes over 10 s or 2 GiB to parse is a finding.
status=0
"$build/sphclip_scene_fuzzer" "$corpus" -dict="$fuzz/scene.dict" \
    -max_total_time="$seconds" -max_len=4096 -rss_limit_mb=2048 -timeout=10 \
    -artifact_prefix="$artifacts" -print_final_stats=1 || status=$?

found=0
for input in "$artifacts"{crash,leak,timeout,oom,slow-unit}-*; do
    [ -e "$input" ] || continue
    cp "$input" "$fuzz/regressions/"
    echo "run_fuzzer: kept $fuzz/regressions/$(basename "$input")"
    found=1
done
rm -f "$artifacts"*
if [ "$status" -ne 0 ] || [ "$found" -ne 0 ]; then
    echo "run_fuzzer: finding(s) above; fix the parser, then rerun" >&2
    exit 1
fi
echo "run_fuzzer: no finding in $seconds s"
