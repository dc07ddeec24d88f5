#!/usr/bin/env bash
# Sanitizer builds and their tests (README, "Sanitizers").
#
#   tools/sanitize.sh [thread|address] [ctest arguments...]
#
# thread (default; what CI runs after tools/test.sh): ThreadSanitizer build in
#   build-tsan/ with clang (so its thread-safety analysis runs too), then the
#   tests that start threads of ours under it (below).
# address: AddressSanitizer + UndefinedBehaviorSanitizer build in build-asan/,
#   then the whole suite (not in CI: about 1.5 h on two cores).
#
# A sanitizer report makes the process exit non-zero (TSan/ASan exit code 66,
# UBSan aborts), so the test that met it fails; the reports are in the test's
# output (ctest --output-on-failure). Suppressions and options:
# tools/sanitizers/. Extra arguments go to ctest (e.g. -R LocalMapper).
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
cd "$here"

kind="${1:-thread}"
[ $# -gt 0 ] && shift
case "$kind" in
  thread)
    dir=build-tsan
    # ThreadSanitizer checks what two threads do to one piece of memory, so
    # it runs the tests that start threads of ours; a test on one thread
    # gives it nothing to check and only runs 5-20x slower. They are:
    # - the thread units' own tests: KeyFrameWorker (the mapping thread's
    #   queue), GlobalAdjuster (global adjustment's thread and its hand-over
    #   to the map), DetectionThread and DetectionThreadReal (the detector
    #   thread with a real model);
    # - SlamLoop.ThreadedMapping..: tracking, local mapping, loop closing and
    #   global adjustment threads together over the whole patrol;
    # - CliSlam: `depot slam run` as users run it (threaded mapping, the
    #   detection thread in `full` and `masked`, run-ahead, map saving and
    #   localisation) and its bad-input exits, which stop threads early.
    #   DenseStaticMap.. is left out: synchronous mapping, and the dense
    #   fusion runs on one thread (384 s under TSan).
    # Everything else runs in the normal build (tools/test.sh). A new test
    # that starts a thread belongs in this list.
    select=(-R '^((KeyFrameWorker|GlobalAdjuster|DetectionThread|DetectionThreadReal)\.|SlamLoop\.ThreadedMapping|CliSlam\.)' -E '^CliSlam\.DenseStaticMap')
    # Only the programs holding those tests are built (and depot, which the
    # CLI tests run, and the vocabulary they load). A program missing here
    # shows as "<name>_NOT_BUILT".
    targets=(depot depot_vocabulary slam_core_test slam_detect_test slam_loop_test cli_slam_test)
    # Built with clang: its thread-safety analysis (-Wthread-safety, an
    # error; common/mutex.h) checks the stated locking of every file the
    # build compiles, before TSan watches the same code run.
    compiler=(-DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++)
    ;;
  address)
    dir=build-asan
    select=()
    targets=(all)
    compiler=()
    ;;
  *)
    echo "error: tools/sanitize.sh: '$kind' is not thread or address" >&2
    exit 2
    ;;
esac

bash tools/require-shared-data.sh
bash tools/install-deps.sh

supp="$here/tools/sanitizers"
# The build runs the instrumented depot too (it trains the default
# vocabulary), so the options are set for the build as well as the tests.
export TSAN_OPTIONS="suppressions=$supp/tsan.supp second_deadlock_stack=1 history_size=7 ${TSAN_OPTIONS:-}"
export ASAN_OPTIONS="$(grep -v '^#' "$supp/asan.options" | paste -sd: -):${ASAN_OPTIONS:-}"
export UBSAN_OPTIONS="suppressions=$supp/ubsan.supp print_stacktrace=1 halt_on_error=1 ${UBSAN_OPTIONS:-}"
# print_suppressions=0: the table of suppressions used goes to stderr and
# would break the tests that count a failing command's error lines.
export LSAN_OPTIONS="suppressions=$supp/lsan.supp print_suppressions=0 ${LSAN_OPTIONS:-}"

# The normal build's vocabulary (tools/test.sh makes it) is the one this
# build would train from the same inputs: copy it rather than train it again
# with an instrumented depot.
vocabulary=()
if [ -f build/vocabulary/depot_orb.voc ]; then
  vocabulary=(-DDEPOT_VOCABULARY_SOURCE="$here/build/vocabulary/depot_orb.voc")
fi
start=$(date +%s)
cmake -S . -B "$dir" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DDEPOT_BUILD_TESTS=ON \
  -DDEPOT_BUILD_BENCH=OFF -DDEPOT_BUILD_PYTHON=OFF -DDEPOT_SANITIZE="$kind" "${compiler[@]}" "${vocabulary[@]}" >/dev/null
cmake --build "$dir" -j"$(nproc)" --target "${targets[@]}"
built=$(date +%s)
status=0
ctest --test-dir "$dir" --output-on-failure -j"$(nproc)" "${select[@]}" "$@" || status=$?
end=$(date +%s)
echo "sanitize ($kind): build $((built - start)) s, tests $((end - built)) s"
exit "$status"
