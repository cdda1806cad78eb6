#!/usr/bin/env bash
# Seed corpora of the fuzz targets (issue 20), from the shipped files: scenes/*.json, devices/*.json, the npm meshes,
# a one-triangle glTF (embedded buffer) and its binary twin, and small EXR/HDR/PNG images made by oiiotool from a
# shipped texture. The mesh and image targets read their first byte as the format ('0', '1', '2' are 0, 1, 2 mod 3).
# Usage: make_seeds.sh SOURCE_DIR OUT_DIR
set -euo pipefail
src=$1 out=$2
rm -rf "$out"
mkdir -p "$out"/scene "$out"/mesh "$out"/image "$out"/device_desc
cp "$src"/scenes/*.json "$out"/scene/
cp "$src"/devices/*.json "$out"/device_desc/
for m in bunny/index.js teapot/teapot.js; do
  [ -f "$src/assets/npm/$m" ] && { printf 0; cat "$src/assets/npm/$m"; } > "$out/mesh/npm_$(dirname "$m")"
done
# One triangle: 3 float3 positions (36 bytes) then 3 uint16 indices (6 bytes, padded to 8).
bin_hex='00000000 00000000 00000000 0000803f 00000000 00000000 00000000 0000803f 00000000 00000100 02000000'
bin=$(for w in $bin_hex; do printf '\\x%s\\x%s\\x%s\\x%s' "${w:0:2}" "${w:2:2}" "${w:4:2}" "${w:6:2}"; done)
gltf_json() {  # $1: the buffer's uri entry ("" for a GLB's own chunk)
  printf '{"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],'
  printf '"meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]}],'
  printf '"buffers":[{%s"byteLength":44}],' "$1"
  printf '"bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":36},{"buffer":0,"byteOffset":36,"byteLength":6}],'
  printf '"accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]},'
  printf '{"bufferView":1,"componentType":5123,"count":3,"type":"SCALAR"}]}'
}
b64=$(printf "$bin" | base64 -w0)
{ printf 1; gltf_json "\"uri\":\"data:application/octet-stream;base64,$b64\","; } > "$out/mesh/gltf_triangle"
u32() { printf '\\x%02x\\x%02x\\x%02x\\x%02x' $(($1 & 255)) $((($1 >> 8) & 255)) $((($1 >> 16) & 255)) $((($1 >> 24) & 255)); }
json=$(gltf_json "")
while [ $((${#json} % 4)) -ne 0 ]; do json="$json "; done
total=$((12 + 8 + ${#json} + 8 + 44))
{
  printf 2
  printf 'glTF'; printf "$(u32 2)"; printf "$(u32 $total)"
  printf "$(u32 ${#json})"; printf 'JSON'; printf '%s' "$json"
  printf "$(u32 44)"; printf 'BIN\0'; printf "$bin"
} > "$out/mesh/glb_triangle"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
if command -v oiiotool > /dev/null && [ -f "$src/assets/textures/checker.exr" ]; then
  oiiotool "$src/assets/textures/checker.exr" --resize 8x8 -d float -o "$tmp/a.exr" --ch R,G,B -o "$tmp/a.hdr" \
    -d uint8 -o "$tmp/a.png"
  i=0
  for e in exr hdr png; do
    { printf "$i"; cat "$tmp/a.$e"; } > "$out/image/$e"
    i=$((i + 1))
  done
fi
echo "fuzz seeds: $(find "$out" -type f | wc -l) files in $out"
