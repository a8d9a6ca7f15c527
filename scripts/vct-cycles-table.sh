#!/usr/bin/env bash
# VCT's medium and high presets against Cycles at 256x256 on the three reference scenes
# (../shared/assets/reference): PSNR (sRGB) and FLIP of the converged frame. Prints one Markdown
# row per scene with a column per preset, for renderer/gi/vct/README.md ("Leaving the volume").
#   bash scripts/vct-cycles-table.sh [build/gisandbox] [extra render flags, e.g. --set vct.offset=1.5]
# GIS_SHADER_DIR picks the shaders (another checkout's, to measure before a change).
set -euo pipefail
cd "$(dirname "$0")/.."
bin=${1:-build/gisandbox}
shift || true
ref=../shared/assets/reference
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

score() {  # name, render flags... -> "PSNR / FLIP"
  local name=$1; shift
  "$bin" render --size 256x256 --gi vct --out "$tmp/$name.exr" "$@" >/dev/null 2>&1 ||
    { echo "vct-cycles-table: rendering $name failed" >&2; exit 1; }
  "$bin" diff "$tmp/$name.exr" "$ref/refs/$name/full.exr" | awk '/^PSNR sRGB/ {p = $3} /^FLIP/ {f = $2} END {printf "%.2f / %.3f", p, f}'
}
helmet=(--scene ../shared/assets/gltf/DamagedHelmet/glTF/DamagedHelmet.gltf --camera-pos 0 0 3.2 --look-at 0 0 0
        --fov 40 --background 1 --lighting scene)  # Cycles' setup: a white sky and no other light
echo "| scene | medium PSNR dB / FLIP | high PSNR dB / FLIP |"
echo "|---|---|---|"
for scene in cornell_box cornell_point DamagedHelmet_sky; do
  if [ "$scene" = DamagedHelmet_sky ]; then flags=("${helmet[@]}"); else flags=(--scene "$ref/scenes/$scene/$scene.gltf"); fi
  row="| \`$scene\`"
  for preset in medium high; do row+=" | $(score "$scene" "${flags[@]}" --preset "$preset" "$@")"; done
  echo "$row |"
done
