#!/usr/bin/env bash
# Installs whatever of voxcast's Debian 12 build and run dependencies is missing.
# Sourced by .ci/demo and .ci/run; safe to run again (does nothing when complete).
set -euo pipefail

VOXCAST_PACKAGES=(
  g++ cmake ninja-build pkg-config
  libglm-dev libopenimageio-dev openimageio-tools libopenexr-dev libimath-dev python3-imath
  libgtest-dev libbenchmark-dev libcli11-dev libtomlplusplus-dev nlohmann-json3-dev libpugixml-dev
  libnifti2-dev libgdcm-dev zlib1g-dev
  mricron-data gnuplot-nox
  tcl
  clang libclang-rt-14-dev
  libclang-14-dev
)

# What only the test suite needs (.ci/run sets VOXCAST_TEST_DEPS=1): Debian's
# headless Chromium, which renders the HTML report pages in the test
# Html.ChromiumRendersTheCosimPage (about 45 s to install, docs/extremes.md);
# and Slurm with munge, which the `cluster` step starts on this machine alone
# (.ci/cluster.sh; about 15 s to install).
if [ "${VOXCAST_TEST_DEPS:-0}" = 1 ]; then
  VOXCAST_PACKAGES+=(chromium slurmctld slurmd slurm-client munge)
fi

missing=()
for p in "${VOXCAST_PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "voxcast: installing missing packages: ${missing[*]}"
  SUDO=""
  [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
