#!/usr/bin/env bash
# The main job on a fresh Debian 12 machine: install what is missing, build in
# Release, render the default scenario and show what came out.
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
cd "$here"

bash tools/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DDEPOT_BUILD_TESTS=ON >/dev/null
cmake --build build -j"$(nproc)" --target depot

scenario="${1:-depot_walking_xyz}"
out="out/${scenario}"
echo "== rendering ${scenario} (Kinect-like sensor model) to ${out}"
./build/tools/depot/depot sim render "$scenario" -o "$out" --frames 300 --overwrite
./build/tools/depot/depot sim preview "$out" -o "out/${scenario}_preview.png"
echo "== done: dataset ${out}, contact sheet out/${scenario}_preview.png"
