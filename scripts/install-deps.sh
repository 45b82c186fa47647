#!/usr/bin/env bash
# Installs the Debian 12 packages crowdlab needs, and only those that are missing.
# Usage: scripts/install-deps.sh [--test]   (--test adds the tools the test suite uses)
# Uses sudo when not root. Safe to run repeatedly: it does nothing when everything is present.
set -euo pipefail
cd "$(dirname "$0")/.."

build_pkgs=(
  nodejs npm
  build-essential cmake ninja-build pkg-config git
  libeigen3-dev libyaml-cpp-dev libtinygltf-dev nlohmann-json3-dev
  libopencv-dev libopencv-contrib-dev libmeshoptimizer-dev libavcodec-dev libavformat-dev libavutil-dev libswscale-dev
  libboost-dev libboost-math-dev libcli11-dev libspdlog-dev libfmt-dev libtbb-dev
  libegl-dev libgl-dev libegl-mesa0 libgl1-mesa-dri libgbm1
  libplplot-dev plplot-driver-cairo libfreetype-dev fonts-dejavu-core libx11-dev
  libbenchmark-dev catch2 zlib1g-dev libzip-dev
  libnlopt-dev libpng-dev libssl-dev
)
# Tools the tests drive: a virtual X server and xdotool for the study window, Node.js for the
# Khronos glTF validator, GNU parallel for the sharding test, and Slurm with munge for the real-sbatch
# test (a private single-node cluster, scripts/slurm-single-node.sh; it starts in about a second),
# Chromium, driven headless by the web study's browser test (puppeteer-core, see make web-deps), and
# Info-ZIP unzip, whose `unzip -t` checks the JATOS archives that libzip (libzip-dev) writes.
# Node.js and npm also install jsPsych for `crowdlab export-web` (make deps runs make web-deps).
test_pkgs=(xvfb xdotool x11-apps nodejs npm parallel slurm-wlm munge chromium unzip)

want=("${build_pkgs[@]}")
if [[ ${1:-} == --test ]]; then want+=("${test_pkgs[@]}"); fi

missing=()
for p in "${want[@]}"; do
  # nodejs/npm may come from elsewhere on a developer machine; accept any working binary.
  if [[ $p == nodejs ]] && command -v node >/dev/null; then continue; fi
  if [[ $p == npm ]] && command -v npm >/dev/null; then continue; fi
  status=$(dpkg-query -W -f='${db:Status-Status}' "$p" 2>/dev/null || true)
  [[ $status == installed ]] || missing+=("$p")
done

if ((${#missing[@]})); then
  echo "crowdlab: installing missing Debian packages: ${missing[*]}"
  SUDO=()
  if [[ $(id -u) -ne 0 ]]; then SUDO=(sudo); fi
  export DEBIAN_FRONTEND=noninteractive
  "${SUDO[@]}" apt-get update -qq
  "${SUDO[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
else
  echo "crowdlab: all Debian packages present"
fi

# The Khronos glTF-Validator (npm package gltf-validator), used only by the tests, kept in .tools/.
# Pinned: every 2.x release is a pre-release (2.0.0-dev.*), which a plain "@2" range never matches.
if [[ ${1:-} == --test ]] && [[ ! -f .tools/node_modules/gltf-validator/package.json ]]; then
  if command -v npm >/dev/null; then
    echo "crowdlab: installing gltf-validator into .tools/ for the glTF tests"
    mkdir -p .tools
    npm install --silent --no-audit --no-fund --prefix .tools gltf-validator@2.0.0-dev.3.10 >/dev/null 2>&1 \
      || echo "crowdlab: warning: npm could not install gltf-validator; the validator test will skip"
  fi
fi
