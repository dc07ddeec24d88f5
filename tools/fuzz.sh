#!/usr/bin/env bash
# Fuzzes every reader of outside input with libFuzzer (tests/fuzz/).
#
#   tools/fuzz.sh [--no-build] [SECONDS] [TARGET...]
#
# Configures build-fuzz/ with clang (DEPOT_FUZZ=ON: ASan + UBSan + coverage),
# builds only the fuzz targets and the libraries they need, makes each
# target's seed corpus from the repository's test data, the shared data
# (${DEPOT_SHARED_DATA}, default ../shared/data; read, never copied into the
# repository) and tests/fuzz/corpus/, then runs each target for SECONDS
# (default 60; CI runs 5). Exits non-zero when any target finds a crash, a
# hang (an input over 10 s), a leak or more than 2 GB of memory; the input
# that did it is in build-fuzz/fuzz/TARGET/crashes/ (rerun it with
# `build-fuzz/tests/fuzz/TARGET FILE`). What a target found stays in
# build-fuzz/fuzz/TARGET/corpus/ and seeds its next run.
#
# --no-build: run what is built (ctest -L fuzz in a DEPOT_FUZZ tree).
# Environment: DEPOT_FUZZ_BUILD (the build folder, default build-fuzz),
# DEPOT_FUZZ_LOCK (a file to flock around the build and each target's run,
# for machines whose builds share their cores).
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
cd "$here"
start=$(date +%s)

build=1
if [ "${1:-}" = "--no-build" ]; then
  build=0
  shift
fi
seconds="${1:-60}"
[ $# -gt 0 ] && shift
if ! [[ "$seconds" =~ ^[0-9]+$ ]] || [ "$seconds" -lt 1 ]; then
  echo "error: tools/fuzz.sh: SECONDS '$seconds' is not a whole number >= 1" >&2
  exit 2
fi
dir="${DEPOT_FUZZ_BUILD:-$here/build-fuzz}"
shared="${DEPOT_SHARED_DATA:-$here/../shared/data}"

locked() {
  if [ -n "${DEPOT_FUZZ_LOCK:-}" ]; then
    flock "$DEPOT_FUZZ_LOCK" "$@"
  else
    "$@"
  fi
}

build_seconds=0
if [ "$build" = 1 ]; then
  for tool in clang clang++; do
    if ! command -v "$tool" >/dev/null; then
      echo "error: tools/fuzz.sh: $tool not found; run tools/install-deps.sh (clang, libclang-rt-14-dev)" >&2
      exit 1
    fi
  done
  # -O1 -g with assertions on: readable stacks, fast enough to fuzz.
  locked env CC=clang CXX=clang++ cmake -S . -B "$dir" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -g" -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g" \
    -DDEPOT_FUZZ=ON -DDEPOT_BUILD_TESTS=OFF -DDEPOT_BUILD_BENCH=OFF -DDEPOT_BUILD_PYTHON=OFF >/dev/null
  locked cmake --build "$dir" --target fuzz -j"$(nproc)"
  build_seconds=$(($(date +%s) - start))
fi

targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
  targets=($(cd "$here/tests/fuzz" && ls fuzz_*.cc | sed 's/\.cc$//'))
fi

# The first lines of a text file (the fuzzer mutates small inputs best).
head_of() { head -n 30 "$1" >"$2/$(basename "$1")"; }

# make_seeds TARGET BINARY SEEDS: SEEDS filled from the repository's and the
# shared data (tests/fuzz/corpus/NAME/ is read as it is).
make_seeds() {
  local name="${1#fuzz_}" bin="$2" seeds="$3" f
  rm -rf "$seeds"
  mkdir -p "$seeds"
  case "$name" in
    tum_trajectory | kitti_trajectory | euroc_trajectory)
      [ -f "$shared/tum/fr1_xyz_trajectory/groundtruth.txt" ] &&
        head_of "$shared/tum/fr1_xyz_trajectory/groundtruth.txt" "$seeds" ;;
    tum_association | label_list)
      for f in "$shared"/tum/fr3_associations/fr3_walking_xyz.txt \
        "$shared"/tum/fr1_xyz_trajectory/rgb.txt "$shared"/tum/fr1_xyz_trajectory/depth.txt; do
        [ -f "$f" ] && head_of "$f" "$seeds"
      done ;;
    system_spec) cp scenes/systems/*.yaml "$seeds"/ ;;
    scenario) cp scenarios/*.yaml "$seeds"/ ;;
    detector_config) cp scenes/detectors/*.yaml scenes/segmenters/*.yaml "$seeds"/ ;;
    map_file) DEPOT_FUZZ_WRITE_SEED="$seeds/writer.map" "$bin" >/dev/null 2>&1 ;;
    vocabulary) DEPOT_FUZZ_WRITE_SEED="$seeds/writer.voc" "$bin" >/dev/null 2>&1 ;;
    mcap_bag) DEPOT_FUZZ_WRITE_SEED="$seeds/writer.mcap" "$bin" >/dev/null 2>&1 ;;
    ply_file) DEPOT_FUZZ_WRITE_SEED="$seeds/writer.ply" "$bin" >/dev/null 2>&1 ;;
  esac
  return 0
}

export ASAN_OPTIONS="detect_leaks=1:allocator_may_return_null=0:${ASAN_OPTIONS:-}"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1:${UBSAN_OPTIONS:-}"
# Leaks inside libraries that are not ours (assimp keeps some of what it
# allocates for a rejected PLY) are not findings; ours are.
export LSAN_OPTIONS="suppressions=$here/tests/fuzz/lsan.supp:print_suppressions=0:${LSAN_OPTIONS:-}"

failed=()
summary=()
for t in "${targets[@]}"; do
  bin="$dir/tests/fuzz/$t"
  if [ ! -x "$bin" ]; then
    echo "error: tools/fuzz.sh: $bin not built (configure with -DDEPOT_FUZZ=ON)" >&2
    exit 1
  fi
  work="$dir/fuzz/$t"
  mkdir -p "$work/corpus" "$work/crashes"
  make_seeds "$t" "$bin" "$work/seeds"
  corpora=("$work/corpus" "$work/seeds")
  [ -d "tests/fuzz/corpus/${t#fuzz_}" ] && corpora+=("tests/fuzz/corpus/${t#fuzz_}")
  log="$work/last-run.log"
  t0=$(date +%s)
  rc=0
  locked "$bin" -max_total_time="$seconds" -rss_limit_mb=2048 -timeout=10 \
    -artifact_prefix="$work/crashes/" -print_final_stats=1 "${corpora[@]}" >"$log" 2>&1 || rc=$?
  # Seconds fuzzed (libFuzzer's count, without waiting for the lock).
  ran=$(sed -n 's/^Done [0-9]* runs in \([0-9]*\) second.*/\1/p' "$log" | tail -1)
  [ -n "$ran" ] || ran=$(($(date +%s) - t0))
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  units=$(find "$work/corpus" -type f | wc -l)
  if [ "$rc" != 0 ]; then
    failed+=("$t")
    echo "== $t: FAILED (exit $rc); the report:"
    grep -E 'ERROR|WARNING|fuzz finding|runtime error|Test unit written|SUMMARY|^    #[0-9]' "$log" | head -40
    echo "   full log: $log"
  fi
  summary+=("$(printf '%-24s %5ss %10s execs  corpus %5s  %s' "$t" "$ran" "${execs:-?}" "$units" \
    "$([ "$rc" = 0 ] && echo ok || echo FAILED)")")
done

echo "fuzz: ${#targets[@]} targets, $seconds s each"
printf '  %s\n' "${summary[@]}"
total=$(($(date +%s) - start))
if [ "$build" = 1 ]; then
  echo "fuzz: build ${build_seconds} s, total ${total} s"
else
  echo "fuzz: total ${total} s"
fi
if [ ${#failed[@]} -gt 0 ]; then
  echo "fuzz: ${#failed[@]} target(s) failed: ${failed[*]}" >&2
  exit 1
fi
