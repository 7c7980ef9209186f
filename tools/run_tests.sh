#!/usr/bin/env bash
# Quick start 2: install what is missing, build (release) and run the test suite
# (ctest preset release: every test but the long validation runs, ctest --preset long).
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/install_deps.sh
cmake --preset release >/dev/null
cmake --build --preset release
ctest --preset release "$@"
