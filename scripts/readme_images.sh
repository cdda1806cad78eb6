#!/usr/bin/env bash
# Regenerates the README's pictures from the shipped scenes on the emulated GPU (build/shadetwin must exist):
#   docs/images/bunny.png   the default scene (the run command's render), 384 x 384
#   docs/images/teapot.png  scenes/teapot.json at 384 x 256 (welded normals: no seams at the patch borders)
# Usage: bash scripts/readme_images.sh
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
build/shadetwin render scenes/bunny.json --width 384 --height 384 --out "$tmp/bunny.exr"
build/shadetwin render scenes/teapot.json --width 384 --height 256 --out "$tmp/teapot.exr"
mkdir -p docs/images
cp "$tmp/bunny.png" docs/images/bunny.png
cp "$tmp/teapot.png" docs/images/teapot.png
echo "wrote docs/images/bunny.png and docs/images/teapot.png"
