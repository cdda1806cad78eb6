#!/usr/bin/env bash
# shadetwin set-up: installs the Debian packages the project needs (skipping what is present) and
# fetches the real assets into the ignored cache folder `assets/`. Idempotent; safe to re-run.
#   assets/hdri/*.exr        CC0 studio-light worlds from Debian's blender-data (forest, courtyard, ...)
#   assets/hdri/LICENSE      their licence text
#   assets/npm/bunny, teapot the npm packages `bunny` and `teapot` (meshes)
#   assets/swiftshader/      SwiftShader (Google's CPU Vulkan driver; Apache-2.0) from the npm package
#                            @sparticuz/chromium, pinned: libvk_swiftshader.so, vk_swiftshader_icd.json,
#                            LICENSE (the package's), VERSION; the project registers the ICD itself
#   assets/textures/*.exr    material maps generated with oiiotool (test patterns, not fetched): a
#                            checker albedo and a roughness ramp, 512x512 float
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cache="$root/assets"

pkgs=(build-essential cmake ninja-build pkg-config fonts-dejavu-core
      libembree-dev libopenimageio-dev openimageio-tools libtbb-dev
      libbenchmark-dev libgtest-dev libgmock-dev
      libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers vulkan-tools glslc spirv-tools
      libcli11-dev nlohmann-json3-dev libtinygltf-dev libeigen3-dev brotli
      clang libclang-rt-14-dev libxml2-utils python3-jsonschema
      slurm-wlm munge chromium)  # clang: the fuzz build (libFuzzer, ASan/UBSan runtimes of clang 14); slurm-wlm, munge:
                                 # the single-node Slurm of the campaign tests; chromium: the report page's browser check
missing=()
for p in "${pkgs[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || missing+=("$p")
done
# npm comes with Node.js; Debian's npm package conflicts with other Node.js builds, so only ask for it when absent.
command -v npm >/dev/null 2>&1 || missing+=(npm)
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}"
  sudo_=""; [ "$(id -u)" = 0 ] || sudo_=sudo
  $sudo_ apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo_ apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
else
  echo "setup: all ${#pkgs[@]} Debian packages present"
fi

mkdir -p "$cache/hdri" "$cache/npm"
if ! ls "$cache/hdri/"*.exr >/dev/null 2>&1; then
  tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
  (cd "$tmp" && apt-get download blender-data >/dev/null)
  dpkg-deb --fsys-tarfile "$tmp"/blender-data_*.deb |
    tar -x -C "$tmp" --wildcards './usr/share/blender/datafiles/studiolights/world/*' './usr/share/doc/blender-data/copyright'
  cp "$tmp"/usr/share/blender/datafiles/studiolights/world/*.exr "$cache/hdri/"
  cp "$tmp"/usr/share/doc/blender-data/copyright "$cache/hdri/LICENSE"
fi
for m in bunny teapot; do
  if [ ! -f "$cache/npm/$m/package.json" ]; then
    (cd "$cache/npm" && tgz=$(npm pack "$m" --silent 2>/dev/null | tail -n1) && mkdir -p "$m" &&
       tar -xzf "$tgz" -C "$m" --strip-components=1 && rm -f "$tgz")
  fi
done
swiftshader_pkg="@sparticuz/chromium@147.0.0"  # pinned (issue 18); bin/swiftshader.tar.br inside
if [ ! -f "$cache/swiftshader/vk_swiftshader_icd.json" ] || [ "$(cat "$cache/swiftshader/VERSION" 2>/dev/null)" != "$swiftshader_pkg" ]; then
  tmp_ss=$(mktemp -d)
  (cd "$tmp_ss" && tgz=$(npm pack "$swiftshader_pkg" --silent 2>/dev/null | tail -n1) &&
     tar -xzf "$tgz" package/bin/swiftshader.tar.br package/LICENSE &&
     brotli -d -c package/bin/swiftshader.tar.br | tar -x libvk_swiftshader.so vk_swiftshader_icd.json)
  mkdir -p "$cache/swiftshader"
  cp "$tmp_ss/libvk_swiftshader.so" "$tmp_ss/vk_swiftshader_icd.json" "$cache/swiftshader/"
  cp "$tmp_ss/package/LICENSE" "$cache/swiftshader/LICENSE"
  echo "$swiftshader_pkg" > "$cache/swiftshader/VERSION"
  rm -rf "$tmp_ss"
fi
mkdir -p "$cache/textures"
if [ ! -f "$cache/textures/roughness_ramp.exr" ]; then
  oiiotool --pattern checker:width=32:height=32:color1=0.9,0.6,0.2:color2=0.15,0.25,0.6 512x512 3 -d float \
    -o "$cache/textures/checker.exr"
  oiiotool --pattern fill:left=0.1,0.1,0.1:right=1,1,1 512x512 3 -d float -o "$cache/textures/roughness_ramp.exr"
fi
echo "setup: assets in $cache: $(ls "$cache/hdri" | grep -c exr) HDRIs, meshes: $(ls "$cache/npm" | tr '\n' ' '), SwiftShader $(cat "$cache/swiftshader/VERSION")"
