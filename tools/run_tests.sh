#!/usr/bin/env bash
# Quick start 2: install what is missing, build (release) and run the whole ctest suite.
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/install_deps.sh
cmake --preset release >/dev/null
cmake --build --preset release
ctest --preset release "$@"
