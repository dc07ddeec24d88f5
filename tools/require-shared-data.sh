#!/usr/bin/env bash
# Stops with one clear line when the shared real data (detector weights, TUM
# timestamps and trajectories) is missing: both README commands need it.
# It is ../shared/data beside the checkout, or $DEPOT_SHARED_DATA.
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
data="${DEPOT_SHARED_DATA:-$here/../shared/data}"
if [ ! -d "$data/models" ] || [ ! -d "$data/tum" ]; then
  echo "error: shared real data not found at $data (no models/ and tum/ there); set DEPOT_SHARED_DATA to that folder, e.g. DEPOT_SHARED_DATA=/path/to/shared/data tools/test.sh" >&2
  exit 1
fi
