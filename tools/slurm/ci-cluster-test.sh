#!/usr/bin/env bash
# The `cluster` tests against a real single-node Slurm started for them:
# starts tools/slurm/local-cluster.sh in a fresh state folder, runs
# `ctest -L cluster` on an already built tree (tools/test.sh builds it), and
# stops the daemons however the tests end (trap), so none outlives the run.
#   tools/slurm/ci-cluster-test.sh [BUILD_DIR] [extra ctest arguments...]
set -euo pipefail
here="$(cd "$(dirname "$0")/../.." && pwd)"
build="${1:-$here/build}"
shift || true

state="$(mktemp -d /tmp/depot-slurm.XXXXXX)"
cleanup() {
  "$here/tools/slurm/local-cluster.sh" stop "$state" || true
  rm -rf "$state"
}
trap cleanup EXIT INT TERM

"$here/tools/slurm/local-cluster.sh" start "$state"
export SLURM_CONF="$state/slurm.conf"
export DEPOT_SLURM=1  # the tests must not skip: the cluster is here
ctest --test-dir "$build" --output-on-failure -L cluster "$@"
