#!/usr/bin/env bash
# The main job on a fresh Debian 12 machine: install what is missing, build in
# Release, render the default scenario and show what came out.
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
cd "$here"

bash tools/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DDEPOT_BUILD_TESTS=ON >/dev/null
cmake --build build -j"$(nproc)" --target depot

depot=./build/tools/depot/depot
scenario="${1:-depot_walking_xyz}"
out="out/${scenario}"
echo "== rendering ${scenario} (Kinect-like sensor model) to ${out}"
"$depot" sim render "$scenario" -o "$out" --frames 300 --overwrite
"$depot" sim preview "$out" -o "out/${scenario}_preview.png"
echo "== SLAM (plain ORB-SLAM2, no rejection) on ${out}"
"$depot" slam run "$out" -o "out/${scenario}_orb.txt"
echo "== ATE against the simulator's ground truth"
"$depot" eval ate "$out/groundtruth.txt" "out/${scenario}_orb.txt" --plot "out/${scenario}_orb_ate.svg" \
  --json "out/${scenario}_orb_ate.json"
echo "== done: dataset ${out}, contact sheet out/${scenario}_preview.png, ATE plot out/${scenario}_orb_ate.svg"
