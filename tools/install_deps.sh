#!/usr/bin/env bash
# Install the Debian packages Fracas needs, if any is missing (as root, or via sudo).
#   bash tools/install_deps.sh [--paraview]
set -euo pipefail
packages=(gfortran gcc cmake make liblapack-dev libhdf5-dev libsuitesparse-dev libmetis-dev zlib1g-dev python3
          python3-numpy python3-h5py python3-matplotlib python3-pytest python3-vtk9 python3-gmsh
          python3-scipy)
# --paraview: also ParaView's Python and a virtual X server, for headless pictures and
# the ctest tools.paraview_render (about 85 MB to download; python3-paraview replaces
# python3-vtk9 and provides the same vtkmodules).
if [ "${1:-}" = "--paraview" ]; then
  packages=("${packages[@]/python3-vtk9/python3-paraview}" xvfb)
fi
installed() { dpkg-query -W -f='${Status}' "$1" 2>/dev/null | grep -q "install ok installed"; }
missing=()
for p in "${packages[@]}"; do
  if [ "$p" = python3-vtk9 ] && installed python3-paraview; then continue; fi
  installed "$p" || missing+=("$p")
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
