#!/usr/bin/env bash
# The run command: set-up, build, then the main job. Until `shadetwin render` lands (issue 3) the
# main job is the differential verification of the foundation against lavapipe.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
bash scripts/setup.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$(nproc)"
build/shadetwin verify math --count "${COUNT:-1000000}"
build/shadetwin verify texture --count "${COUNT_TEX:-100000}" --finite --filters texelFetch,nearest,nearest-miplin,bilinear,trilinear
