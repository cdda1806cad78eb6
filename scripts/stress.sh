#!/usr/bin/env bash
# Issue 20 item 6: the stress runs of docs/RESULTS.md "Stress". Generates a 2,000,000-triangle glTF sphere and an
# 8192x4096 environment (the CC0 forest map resized by oiiotool), then renders each, and the bunny at 4096x4096, on the
# emulator and on lavapipe; every render prints its time and peak memory (the last line of each log).
#   usage: scripts/stress.sh [BUILD_DIR] [WORK_DIR] [DEVICES...]   (defaults: build, build/stress, emu vulkan)
set -euo pipefail
cd "$(dirname "$0")/.."
B=${1:-build}
W=${2:-build/stress}
shift $(( $# > 2 ? 2 : $# ))
DEVICES=("$@")
[ ${#DEVICES[@]} -gt 0 ] || DEVICES=(emu vulkan)
mkdir -p "$W/scenes"
ln -sfn "$(pwd)/assets" "$W/assets"
[ -f "$W/scenes/sphere2m.glb" ] || python3 scripts/make_stress_mesh.py "$W/scenes/sphere2m.glb" --rings 1000 --sectors 1000
[ -f "$W/env8k.exr" ] || oiiotool assets/hdri/forest.exr --resize 8192x4096 -d float -o "$W/env8k.exr"
cat > "$W/scenes/mesh2m.json" <<'JSON'
{
  "description": "Stress (issue 20): a 2,000,000-triangle sphere (scripts/make_stress_mesh.py) on the bunny's plinth, FIS with 16 shadow maps.",
  "image": {"width": 1024, "height": 1024},
  "camera": {"eye": [0.0, 1.0, 2.9], "target": [0.0, 0.4, 0.0], "fov": 38, "near": 0.5, "far": 10},
  "environment": {"file": "../assets/hdri/forest.exr"},
  "technique": "fis",
  "visibility": {"maps": 16, "size": 1024},
  "materials": [{"name": "porcelain", "diffuse": [0.72, 0.70, 0.66], "specular": [0.05, 0.05, 0.05], "exponent": 300},
                {"name": "stone", "diffuse": [0.35, 0.33, 0.30], "specular": [0.02, 0.02, 0.02], "exponent": 20}],
  "objects": [{"mesh": "sphere2m.glb", "material": "porcelain", "fit": 1.0},
              {"mesh": "plane", "material": "stone", "scale": 0.6}]
}
JSON
sed -e 's|"../assets/hdri/forest.exr"|"../env8k.exr"|' -e 's|"description": "[^"]*"|"description": "Stress (issue 20): scenes/bunny.json under the forest map resized to 8192x4096."|' \
  scenes/bunny.json > "$W/scenes/env8k.json"
cp scenes/bunny.json "$W/scenes/bunny.json"
for dev in "${DEVICES[@]}"; do
  for run in "mesh2m" "env8k" "bunny4k"; do
    args=("$W/scenes/$run.json")
    [ "$run" = bunny4k ] && args=("$W/scenes/bunny.json" --width 4096 --height 4096)
    echo "== $run on $dev"
    "$B/shadetwin" render "${args[@]}" --device "$dev" --out "$W/${run}_$dev.exr" 2>&1 | tee "$W/${run}_$dev.log" | grep -E "memory|scene |environment \+|G-buffer|shadow maps|shading|wrote" || true
  done
done
