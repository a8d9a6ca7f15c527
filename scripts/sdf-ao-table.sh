#!/usr/bin/env bash
# sdf's near-field occlusion (sdf.ao) against the truth, for renderer/gi/sdf/README.md: each scene
# rendered by `--gi sdf` (defaults otherwise) at every value of AO_VALUES (default "1 0") and scored
# PSNR (sRGB) / FLIP against its reference: Cycles' full.exr for the three reference scenes
# (../shared/assets/reference, 256x256), the path tracer (PT_SPP samples, default 256, 16 bounces)
# for builtin:atrium, whose columns and arches are finer than a probe cell, where contact occlusion
# could still add what the probes miss (SIZE, default 128x128). Prints one Markdown row per scene.
#   bash scripts/sdf-ao-table.sh [build/gisandbox] [extra sdf render flags, e.g. --set sdf.diffuse=rays]
set -euo pipefail
cd "$(dirname "$0")/.."
bin=${1:-build/gisandbox}
shift || true
values=${AO_VALUES:-1 0}
size=${SIZE:-128x128}
spp=${PT_SPP:-256}
ref=../shared/assets/reference
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

render() {  # out, flags...
  local out=$1; shift
  "$bin" render --out "$out" "$@" >/dev/null 2>&1 || { echo "sdf-ao-table: rendering $out failed" >&2; exit 1; }
}
score() {  # image, reference -> "PSNR / FLIP"
  "$bin" diff "$1" "$2" | awk '/^PSNR sRGB/ {p = $3} /^FLIP/ {f = $2} END {printf "%.2f / %.3f", p, f}'
}
helmet=(--scene ../shared/assets/gltf/DamagedHelmet/glTF/DamagedHelmet.gltf --camera-pos 0 0 3.2 --look-at 0 0 0
        --fov 40 --background 1 --lighting scene)  # Cycles' setup: a white sky and no other light
header="| scene (reference) |"; rule="|---|"
for v in $values; do header+=" sdf.ao=$v PSNR dB / FLIP |"; rule+="---|"; done
echo "$header"; echo "$rule"
for scene in cornell_box cornell_point DamagedHelmet_sky atrium; do
  case $scene in
    DamagedHelmet_sky) flags=("${helmet[@]}" --size 256x256) ;;
    atrium) flags=(--scene builtin:atrium --size "$size") ;;
    *) flags=(--scene "$ref/scenes/$scene/$scene.gltf" --size 256x256) ;;
  esac
  if [ "$scene" = atrium ]; then
    truth="$tmp/atrium_pt.exr"
    render "$truth" "${flags[@]}" --gi pathtrace --set "pathtrace.spp=$spp" --set pathtrace.bounces=16
    row="| \`builtin:atrium\` (path tracer, $spp spp, $size)"
  else
    truth="$ref/refs/$scene/full.exr"
    row="| \`$scene\` (Cycles)"
  fi
  for v in $values; do
    render "$tmp/$scene.$v.exr" "${flags[@]}" --gi sdf "$@" --set "sdf.ao=$v"
    row+=" | $(score "$tmp/$scene.$v.exr" "$truth")"
  done
  echo "$row |"
done
