#!/usr/bin/env bash
# The run command (the main job): set-up, build, then render the default scene (scenes/bunny.json)
# on the emulated GPU to bunny.exr and bunny.png, printing the time of every pass.
# Extra arguments go to `shadetwin render` (e.g. scenes/spheres.json --out out/spheres.exr).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
bash scripts/setup.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$(nproc)"
build/shadetwin render "$@"
