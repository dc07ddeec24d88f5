#!/usr/bin/env bash
# The main job on a fresh Debian 12 machine: install what is missing, build in
# Release, render the default scenario, run the paper's four modes and our
# `masked` on it, print the ablation table with the improvement over orb
# (Eq. 9) and write the HTML report.
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
cd "$here"

bash tools/require-shared-data.sh
bash tools/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DDEPOT_BUILD_TESTS=ON >/dev/null
cmake --build build -j"$(nproc)" --target depot depot_vocabulary

depot=./build/tools/depot/depot
scenario="${1:-depot_walking_xyz}"
out="out/${scenario}"
# A previous main job's folder is replaced; anything else is left alone.
if [ -e "$out" ]; then
  if [ ! -f "$out/sweep.json" ]; then
    echo "setup: error: $out exists and is not a sweep folder; move it away first" >&2
    exit 1
  fi
  for entry in "$out"/* "$out"/.[!.]*; do
    [ -e "$entry" ] || continue
    case "$(basename "$entry")" in
      sweep.json | data | runs | logs | report | preview.png | .*.partial-*) ;;
      *)
        echo "setup: error: $out holds $(basename "$entry"), which the main job did not write; move it away first" >&2
        exit 1
        ;;
    esac
  done
  rm -rf "$out"
fi
echo "== ${scenario}: render 300 frames (640x480, Kinect-like sensor), then SLAM in modes orb, orb+yolo, orb+lk, full, masked"
"$depot" sweep run "$scenario" -o "$out" --seeds 1 --frames 300 --keep-data -j "$(nproc)" \
  --modes orb,orb+yolo,orb+lk,full,masked
dataset="${out}/data/${scenario}__s1"
"$depot" sim preview "$dataset" -o "${out}/preview.png"
echo "== done: report ${out}/report/report.html, dataset ${dataset}, contact sheet ${out}/preview.png"
