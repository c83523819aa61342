#!/usr/bin/env bash
# Fuzzes the scene loader with libFuzzer (clang-14, AddressSanitizer, UBSan) for a bounded
# time, seeded with every built-in scene and a JSON dictionary. Any crash, leak, timeout or
# sanitizer report fails the run, and the input is copied to fuzz/regressions/ so the unit
# tests replay it from then on. Usage: scripts/fuzz.sh [SECONDS] (default 60).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
jobs=$(nproc)
CXX=clang++-14 CC=clang-14 cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DPBA_FUZZ=ON \
  -DPBA_BUILD_APP=OFF -DPBA_BUILD_TESTS=OFF -DPBA_BUILD_BENCH=OFF > /dev/null
cmake --build build-fuzz -j "$jobs" --target scene_loader_fuzz
corpus=$(mktemp -d)
artifacts=$(mktemp -d)
trap 'rm -rf "$corpus" "$artifacts"' EXIT
cp scenes/*.json "$corpus"/
cp fuzz/regressions/*.json "$corpus"/ 2>/dev/null || true
export ASAN_OPTIONS="halt_on_error=1:detect_leaks=1"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
status=0
build-fuzz/fuzz/scene_loader_fuzz -dict=fuzz/json.dict -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
  -max_len=4096 -print_final_stats=1 -artifact_prefix="$artifacts/" "$corpus" 2>&1 | tail -n 25 || status=$?
if [ "$status" -ne 0 ]; then
  for f in "$artifacts"/*; do
    [ -e "$f" ] || continue
    cp "$f" "fuzz/regressions/$(basename "$f").json"
    echo "fuzz: kept $(basename "$f") in fuzz/regressions/ (commit it)"
  done
  echo "fuzz: FAILED (exit $status)"
  exit 1
fi
echo "fuzz: no crash, leak, timeout or sanitizer report in ${seconds} s"
