#!/usr/bin/env bash
# Sanitizer builds and their tests (README, "Sanitizers").
#
#   tools/sanitize.sh [thread|address] [ctest arguments...]
#
# thread (default; what CI runs after tools/test.sh): ThreadSanitizer build in
#   build-tsan/, then `ctest -L slam` under it.
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
    # Left out (TSan makes them 15-25x slower, and they run on one thread,
    # so it has nothing to check in them; the normal build runs them):
    # - SimDetectorTest.*: the simulated detector's statistics on rendered
    #   frames (~200 s each, 15 of them; no threads of ours but the
    #   simulator's PNG writers);
    # - the synchronous-mapping accuracy runs, > 10 min each: SlamSystem's
    #   StaticDepot.. and RealHandHeldFr1Xyz.., SlamLoop's RelocalisesAgainst..
    #   and TheLoopIsClosed.. (the patrol);
    # - two threaded runs whose threads other tests cover, to keep CI's
    #   TSan step near 15 minutes (they took 384 s and 604 s under TSan):
    #   SlamSystem.WalkingPeopleWithoutRejection.. (mapping thread: the
    #   patrol below) and RejectSystem.FullModeBeats.. (detection thread:
    #   the DetectionThread unit tests and CliSlam's full and masked runs).
    # - CliSlam.DenseStaticMap..: three `full` runs and three cloud scorings
    #   at 320 px with synchronous mapping (the detection thread is CliSlam's
    #   other full runs'; the dense fusion runs on one thread).
    # The threaded runs that stay: SlamLoop.ThreadedMapping.. (mapping, loop
    # closing and global adjustment threads over the whole patrol), the
    # KeyFrameWorker, GlobalAdjuster and DetectionThread unit tests, CliSlam
    # (depot slam run, threaded by default, full and masked modes).
    select=(-L slam -E '^(SimDetectorTest\.|SlamSystem\.(StaticDepot|RealHandHeld|WalkingPeople)|SlamLoop\.(RelocalisesAgainst|TheLoopIsClosed)|RejectSystem\.FullModeBeats|CliSlam\.DenseStaticMap)')
    # Only what those tests run is built (the sim, eval, harness and CLI
    # error tests are not; about a fifth of an instrumented build). A new
    # slam-labelled test program missing here shows as "<name>_NOT_BUILT".
    targets=(depot depot_vocabulary apriori_tables_test cli_rejection_test cli_slam_test
      cli_system_test perception_test reject_real_frame_test reject_system_test slam_core_test
      slam_data_test slam_dense_test slam_detect_test slam_detect_sim_test slam_feature_test
      slam_loop_test slam_map_test slam_match_test slam_optimize_test slam_place_test
      slam_reject_test slam_system_test)
    ;;
  address)
    dir=build-asan
    select=()
    targets=(all)
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
  -DDEPOT_BUILD_BENCH=OFF -DDEPOT_SANITIZE="$kind" "${vocabulary[@]}" >/dev/null
cmake --build "$dir" -j"$(nproc)" --target "${targets[@]}"
built=$(date +%s)
status=0
ctest --test-dir "$dir" --output-on-failure -j"$(nproc)" "${select[@]}" "$@" || status=$?
end=$(date +%s)
echo "sanitize ($kind): build $((built - start)) s, tests $((end - built)) s"
exit "$status"
