#!/usr/bin/env bash
# Builds the whole test suite with AddressSanitizer and UndefinedBehaviorSanitizer and runs it;
# the first report stops the run (halt_on_error, -fno-sanitize-recover=all).
# With clang-14, as the fuzzer: it builds and runs the suite about three times faster than GCC 12,
# which compiles swarm.cpp's loops once per instruction set (target_clones), each instrumented;
# the clones are the same source as the one loop clang builds and checks.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc)
source scripts/compiler-cache.sh
cmake -S . -B build-asan -G Ninja -DCMAKE_CXX_COMPILER=clang++-14 \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo -DPBA_SANITIZE=ON -DPBA_BUILD_BENCH=OFF "${cache_flags[@]}"
cmake --build build-asan -j "$jobs"
export ASAN_OPTIONS="halt_on_error=1:abort_on_error=1:detect_leaks=1:strict_string_checks=1"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
# Mesa's driver (llvmpipe) and libEGL keep caches alive until exit; those are not ours.
export LSAN_OPTIONS="suppressions=$PWD/scripts/lsan.supp:print_suppressions=0"
gl='^(PbaRender|PbaView|HeadlessRender|RenderClock|Security|Outputs)\.|^NumericFlagsDecimal\.LeadingZerosAreRead$'
# The install test links an uninstrumented consumer against these instrumented libraries: it
# tests packaging, which the plain build already does. The simulated hours (tunnelling, soak)
# run the same code as the short tests 10^4 times over; unvectorised and checked at every load
# they would take most of CI's half hour, so they run in the plain build only; so does the
# crowded-block comparison (110 s here against 12 s plain), whose crowded blocks the swarm
# scenes' tests step here too. The scene claims, the thousand-dice piles, the quick bench and
# the work-precision study run here (about a minute and a half more than without them).
long='^(Tunnelling|Soak)\.|^Swarm\.CrowdedBlocksGetTheSameRuleAsParticlesAlone$'
ctest --test-dir build-asan --output-on-failure -j "$jobs" -E "$gl|^install\.|$long"
# The OpenGL tests (and the output tests and the leading-zeros one, whose pba children render)
# run with address and UB checks but without leak checks: llvmpipe's JIT-compiled
# code allocates from frames LeakSanitizer cannot name, so its leaks cannot be told from ours.
ASAN_OPTIONS="$ASAN_OPTIONS:detect_leaks=0" ctest --test-dir build-asan --output-on-failure -j "$jobs" -R "$gl"
