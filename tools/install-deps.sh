#!/usr/bin/env bash
# Installs the Debian 12 packages depot-slam needs, only those missing.
# Idempotent; uses sudo when not root. Nothing is downloaded outside apt.
# chromium renders the HTML report in a headless screenshot test; opencv-doc
# ships the sample photographs the default vocabulary is trained on.
# python3-open3d runs the shipped example system under test
# (scenes/systems/open3d_odometry), a dense RGB-D odometry baseline.
# slurm-wlm and munge run the local single-node cluster of .ci/run's cluster
# step (tools/slurm/local-cluster.sh); clang and libclang-rt-14-dev build the
# libFuzzer targets (tests/fuzz, `fuzz` label); ccache speeds up rebuilds;
# libfmt-dev formats text (numbers into tables, files and messages);
# libzstd-dev and liblz4-dev compress the chunks of ROS 2 bags (MCAP), and
# nodejs with npm runs the independent MCAP/CDR readers the bag tests check
# our files with (their packages come from the npm registry, pinned in
# tests/mcap/package-lock.json, into the build folder); pybind11-dev builds
# `import depot` for Debian's python3, whose numpy and pytest its tests use.
set -euo pipefail

packages=(
  build-essential cmake pkg-config
  libmujoco-dev libqhull-dev
  libgl-dev libopengl-dev libosmesa6-dev libegl-dev libegl-mesa0 libgl1-mesa-dri
  libopencv-dev libpng-dev zlib1g-dev libeigen3-dev libceres-dev libassimp-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libyaml-cpp-dev libcli11-dev nlohmann-json3-dev libfmt-dev
  chromium opencv-doc
  python3-open3d
  slurm-wlm munge
  clang libclang-rt-14-dev ccache
  libzstd-dev liblz4-dev
  nodejs
  pybind11-dev python3-dev python3-numpy python3-pytest
)
# A nodejs from NodeSource bundles npm (and conflicts with Debian's npm):
# Debian's npm only where no npm is on the path.
if ! command -v npm > /dev/null 2>&1; then packages+=(npm); fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi
echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
