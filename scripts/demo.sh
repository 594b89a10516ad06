#!/usr/bin/env bash
# Sets up, builds and runs the default demo scene (a 2D column collapse) into
# out/collapse2d; open out/collapse2d/series.pvd in ParaView.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
build/sablier run scenes/collapse2d.toml --out out/collapse2d --format vtp,csv --overwrite
