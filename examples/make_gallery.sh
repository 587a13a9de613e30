#!/usr/bin/env bash
# Regenerates the examples' gallery (docs/LIBRARY.md): runs every example (ctest's example_*
# tests, which write their PNGs into BUILD_DIR/examples/gallery) and copies the PNGs to
# examples/gallery/.
# Usage: bash examples/make_gallery.sh [BUILD_DIR]   (default build/ci; build it first)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build/ci}
ctest --test-dir "$build" -R '^example_[0-9][0-9]_' --output-on-failure >/dev/null
mkdir -p examples/gallery
for png in "$build"/examples/gallery/[0-9][0-9]_*.png; do
  cp "$png" examples/gallery/
  echo "examples/gallery/$(basename "$png")"
done
