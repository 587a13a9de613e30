#!/usr/bin/env bash
# Regenerates the README's gallery: runs every example and writes its PNG to examples/gallery/.
# Usage: bash examples/make_gallery.sh [BUILD_DIR]   (default build/ci; build it first)
set -euo pipefail
cd "$(dirname "$0")/.."
bin=${1:-build/ci}/bin/examples
mkdir -p examples/gallery
for example in "$bin"/[0-9][0-9]_*; do
  name=$(basename "$example")
  if [[ $name == 00_hello ]]; then
    continue  # prints, draws nothing (README: "Using fixstep as a library")
  elif [[ $name == 06_window ]]; then
    SDL_VIDEODRIVER=dummy "$example" 30 "examples/gallery/$name.png" >/dev/null
  else
    "$example" "examples/gallery/$name.png" >/dev/null
  fi
  echo "examples/gallery/$name.png"
done
