#!/usr/bin/env bash
# Quick start 1: install what is missing, build (release) the fracas program only, run the
# default demo deck.
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/install_deps.sh
cmake --preset release >/dev/null
cmake --build --preset release --target fracas
build/release/bin/fracas --overwrite --output build/demo test_cases/examples/demo_deposit
