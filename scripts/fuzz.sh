#!/usr/bin/env bash
# Fuzzes with libFuzzer (clang-14, AddressSanitizer, UBSan) for a bounded time: the scene loader,
# seeded with every built-in scene and a JSON dictionary, then the command line's scene options
# and the CSV writer for a third of that time. Any crash, leak, timeout or sanitizer report fails
# the run, and the input is copied to fuzz/regressions/ (scenes, replayed by the unit tests) or
# fuzz/command_line_seeds/ (replayed by the next fuzz run). Usage: scripts/fuzz.sh [SECONDS] (60).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
jobs=$(nproc)
source scripts/compiler-cache.sh
CXX=clang++-14 CC=clang-14 cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DPBA_FUZZ=ON \
  -DPBA_BUILD_APP=OFF -DPBA_BUILD_TESTS=OFF -DPBA_BUILD_BENCH=OFF "${cache_flags[@]}" > /dev/null
cmake --build build-fuzz -j "$jobs" --target scene_loader_fuzz command_line_fuzz
export ASAN_OPTIONS="halt_on_error=1:detect_leaks=1"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"

# fuzz TARGET SECONDS KEEP_DIR KEEP_SUFFIX SEED_DIR... : runs one target on a fresh corpus.
fuzz() {
  local target=$1 time=$2 keep=$3 suffix=$4
  shift 4
  local corpus artifacts status=0
  corpus=$(mktemp -d)
  artifacts=$(mktemp -d)
  for seeds in "$@"; do cp "$seeds"/* "$corpus"/ 2>/dev/null || true; done
  local dict=()
  [ "$target" = scene_loader_fuzz ] && dict=(-dict=fuzz/json.dict)
  "build-fuzz/fuzz/$target" "${dict[@]}" -max_total_time="$time" -timeout=10 -rss_limit_mb=2048 -max_len=4096 \
    -print_final_stats=1 -artifact_prefix="$artifacts/" "$corpus" 2>&1 | tail -n 25 || status=$?
  if [ "$status" -ne 0 ]; then
    for f in "$artifacts"/*; do
      [ -e "$f" ] || continue
      cp "$f" "$keep/$(basename "$f")$suffix"
      echo "fuzz: kept $(basename "$f") in $keep/ (commit it)"
    done
    rm -rf "$corpus" "$artifacts"
    echo "fuzz: $target FAILED (exit $status)"
    exit 1
  fi
  rm -rf "$corpus" "$artifacts"
  echo "fuzz: $target: no crash, leak, timeout or sanitizer report in ${time} s"
}

fuzz scene_loader_fuzz "$seconds" fuzz/regressions .json scenes fuzz/regressions
fuzz command_line_fuzz $(( (seconds + 2) / 3 )) fuzz/command_line_seeds "" fuzz/command_line_seeds
