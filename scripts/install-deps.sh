#!/usr/bin/env bash
# Installs what erkn needs from Debian, if anything is missing (apt-get, as root or via sudo).
set -euo pipefail
packages=(g++ cmake make pkg-config git libginac-dev libcln-dev libeigen3-dev googletest
          libgtest-dev libbenchmark-dev libboost-dev gnuplot-nox
          libfftw3-dev libfftw3-mpi-dev libopenmpi-dev openmpi-bin
          pybind11-dev python3-dev python3-numpy python3-scipy python3-mpmath python3-pytest
          python3-matplotlib
          python3-venv python3-pip)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "erkn: installing ${missing[*]}"
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq "${missing[@]}" > /dev/null
fi
