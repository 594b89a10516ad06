#!/usr/bin/env bash
# Sets up, builds and runs the default demo scene (a 2D column collapse) into
# out/collapse2d, then draws its frames as PNG pictures in
# out/collapse2d/images (with an animated GIF); open out/collapse2d/series.pvd in ParaView.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
build/sablier run scenes/collapse2d.toml --out out/collapse2d --format vtp,csv --overwrite
build/sablier render out/collapse2d --gif
build/sablier plot out/collapse2d
echo "frames: out/collapse2d/series.pvd (ParaView); pictures and animation.gif: out/collapse2d/images/; stats: out/collapse2d/stats.png"
