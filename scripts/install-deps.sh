#!/usr/bin/env bash
# Installs the build and run dependencies from Debian's packages (run as root on a fresh Debian 12).
set -euo pipefail
packages=(
  cmake ninja-build g++ pkg-config
  libvtk9-dev libopenvdb-dev libboost-iostreams-dev
  libpng-dev libopenexr-dev libfreetype-dev fonts-dejavu-core
  libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers vulkan-tools glslang-tools spirv-tools
  libtbb-dev libcli11-dev nlohmann-json3-dev zlib1g-dev libzstd-dev
  libavcodec-dev libavformat-dev libswscale-dev libavutil-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  gnuplot-nox libvolpack1-dev
  "$@"
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "Installing: ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -q
  apt-get install -y -q --no-install-recommends "${missing[@]}"
fi
