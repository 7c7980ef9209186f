#!/usr/bin/env bash
# Install the Debian packages Fracas needs, if any is missing (as root, or via sudo).
set -euo pipefail
packages=(gfortran gcc cmake make liblapack-dev libhdf5-dev libsuitesparse-dev libmetis-dev zlib1g-dev python3
          python3-numpy python3-h5py python3-matplotlib python3-pytest python3-vtk9 python3-gmsh
          python3-scipy)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi
echo "fracas: installing Debian packages: ${missing[*]}"
if [ "$(id -u)" -eq 0 ]; then
  SUDO=""
elif command -v sudo >/dev/null 2>&1; then
  SUDO="sudo"
else
  echo "fracas: missing packages ${missing[*]} and not root: install them with apt-get" >&2
  exit 1
fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
