#!/usr/bin/env bash
# The main job on a fresh Debian 12 machine: install what is missing, build in
# Release, render the default scenario, run the paper's four modes on it,
# print the ablation table with the improvement of full over orb (Eq. 9) and
# write the HTML report.
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
cd "$here"

bash tools/require-shared-data.sh
bash tools/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DDEPOT_BUILD_TESTS=ON >/dev/null
cmake --build build -j"$(nproc)" --target depot

depot=./build/tools/depot/depot
scenario="${1:-depot_walking_xyz}"
out="out/${scenario}"
rm -rf "$out"
echo "== ${scenario}: render 300 frames (640x480, Kinect-like sensor), then SLAM in modes orb, orb+yolo, orb+lk, full"
"$depot" sweep run "$scenario" -o "$out" --seeds 1 --frames 300 --keep-data -j "$(nproc)"
dataset="${out}/data/${scenario}__s1"
"$depot" sim preview "$dataset" -o "${out}/preview.png"
echo "== done: report ${out}/report/report.html, dataset ${dataset}, contact sheet ${out}/preview.png"
