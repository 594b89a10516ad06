#!/usr/bin/env bash
# Sets up, builds and runs the default test suite (everything but the long
# `validation` runs: `ctest --test-dir build -L validation` runs those).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
ctest --test-dir build -LE validation --output-on-failure
