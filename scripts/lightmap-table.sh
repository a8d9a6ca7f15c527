#!/usr/bin/env bash
# The lightmap page's tables (issue #41), in one sitting, at 256x256:
#   - per scene and preset: PSNR (sRGB) / mean radiance over Cycles' (cornell_box, cornell_point and
#     the atrium courtyard of ../shared/assets/reference), one sample per pixel and --supersample 2
#     (the references' pixel is a box-filtered square: the second scores light, not edges; the bake
#     read from the cache), the bake's wall seconds, its texels and
#     GPU memory (`render --timings` stats), and the frame's median wall ms once baked (a second run
#     reads the bake from the cache) over `--gi none`'s on the same scene;
#   - how the bake grows: builtin:atrium at detail 1, 2, 4 (triangles) and at 4k, 16k, 64k texels,
#     64 paths per texel;
#   - what lightmap.mode=all buys: per scene at medium, indirect against all, the same columns.
# Writes them between the "lightmap-table", "lightmap-growth" and "lightmap-modes" markers of
# renderer/gi/lightmap/README.md.
#
# Usage (project root, after a build): bash scripts/lightmap-table.sh [BIN (build/gisandbox)]
# Environment: PRESETS (low,medium,high); TABLES (presets,growth,modes: which to measure).
set -euo pipefail
case ${1:-} in -h|--help) sed -n '2,/^set -e/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0 ;; esac
cd "$(dirname "$0")/.."
bin=${1:-build/gisandbox}
presets=${PRESETS:-low,medium,high}
tables=${TABLES:-presets,growth,modes}
shared=../shared/assets/reference
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
export GIS_LIGHTMAP_CACHE=$tmp/cache  # every bake fresh, then read back by the frame-cost run

source scripts/table_lib.sh

# "bake seconds|texels|MiB" from a --timings log's lightmap stats.
bakeFacts() {
  awk '/lightmap bake/ {n = split($0, w, " "); s = w[n] == "s" ? w[n - 1] : "?"}
       /texels on surfaces/ {for (i = 1; i <= NF; ++i) {if ($(i + 1) == "texels" && $(i + 2) == "on") t = $i; if ($(i + 1) == "MiB") m = $i}}
       END {printf "%s|%s|%s", s, t, m}' "$1"
}
frameMs() {  # flags... -> median wall ms per frame, every pass executed
  timeout 1800 "$bin" render --out "$tmp/f.png" --timings --frames 30 --warmup 5 "$@" 2>&1 | awk '$1 == "wall" {print $2}'
}

wants() { [[ ",$tables," == *",$1,"* ]]; }
sceneFlags() {  # scene -> the flags that render it as Cycles' reference does
  echo --scene "$shared/scenes/$1/$1.gltf" --size 256x256
  [ "$1" = atrium ] && echo --background 0.35,0.45,0.6  # Cycles' sky (building-table.sh)
  return 0
}
# "| scene | label | against Cycles | bake s | texels | MiB | frame ms (x none) |" for one lightmap run.
row() {  # scene label none-ms flags...
  local scene=$1 label=$2 none=$3
  shift 3
  timeout 7200 "$bin" render --out "$tmp/$scene.exr" --timings "$@" --gi lightmap > "$tmp/log" 2>&1 ||
    { echo "lightmap-table: $scene ($label) failed:" >&2; tail -3 "$tmp/log" >&2; exit 1; }
  IFS='|' read -r seconds texels mib <<< "$(bakeFacts "$tmp/log")"
  ms=$(frameMs "$@" --gi lightmap)
  ratio=$(awk -v a="$ms" -v b="$none" 'BEGIN {printf "%.2f", a / b}')
  timeout 1800 "$bin" render --out "$tmp/$scene-ss.exr" --supersample 2 "$@" --gi lightmap > "$tmp/log" 2>&1 ||
    { echo "lightmap-table: $scene ($label, --supersample 2) failed:" >&2; tail -3 "$tmp/log" >&2; exit 1; }
  echo "| $scene | $label | $(compare "$tmp/$scene.exr" "$shared/refs/$scene/full.exr") |" \
       "$(compare "$tmp/$scene-ss.exr" "$shared/refs/$scene/full.exr") | $seconds | $texels | $mib | $ms ($ratio) |"
}

gl=$("$bin" render --scene builtin:cornell --size 8x8 --out "$tmp/gl.png" -v 2>&1 | sed -n 's/^GL_RENDERER: //p')
header() {
  echo "\`scripts/lightmap-table.sh\`, $(date -u +%Y-%m-%d), ${gl:-unknown GL renderer}, 256x256. PSNR (sRGB) / mean radiance"
  echo "over Cycles', one sample per pixel and \`--supersample 2\` (the references' pixels are box-filtered squares);"
  echo "bake: wall seconds of the whole bake; frame: median wall ms per frame once baked (the bake read from the"
  echo "cache, one sample per pixel), over \`--gi none\`'s on the same scene (llvmpipe: a ratio, not a budget)."
  echo
  echo "| scene | $1 | against Cycles | supersampled 2x2 | bake s | texels | MiB | frame ms (x none) |"
  echo "|---|---|---|---|---|---|---|---|"
}
if wants presets; then
{
  header preset
  for scene in cornell_box cornell_point atrium; do
    mapfile -t flags < <(sceneFlags "$scene" | tr ' ' '\n')
    none=$(frameMs "${flags[@]}" --gi none)
    for p in ${presets//,/ }; do row "$scene" "$p" "$none" "${flags[@]}" --preset "$p"; done
  done
} > "$tmp/table.md"
cat "$tmp/table.md"
/usr/bin/python3 scripts/page_table.py renderer/gi/lightmap/README.md lightmap-table "Against Cycles, bake and frame" "$tmp/table.md"
fi

if wants growth; then
{
  echo "\`scripts/lightmap-table.sh\`, $(date -u +%Y-%m-%d), ${gl:-unknown GL renderer}: builtin:atrium, 64 paths per texel,"
  echo "the bake's wall seconds as its triangles (detail) and its texels (lightmap.texels) grow."
  echo
  echo "| detail | texels | triangles | texels on surfaces | bake s |"
  echo "|---|---|---|---|---|"
  for run in "1 4096" "1 16384" "1 65536" "2 16384" "4 16384"; do
    read -r detail texels <<< "$run"
    timeout 7200 "$bin" render --out "$tmp/g.png" --timings --size 64x64 --scene "builtin:atrium?detail=$detail" --gi lightmap \
      --set lightmap.samples=64 --set "lightmap.texels=$texels" > "$tmp/log" 2>&1 ||
      { echo "lightmap-table: atrium detail $detail failed:" >&2; tail -3 "$tmp/log" >&2; exit 1; }
    triangles=$("$bin" info --scene "builtin:atrium?detail=$detail" 2>/dev/null | awk '/triangles/ {for (i = 1; i < NF; ++i) if ($(i + 1) ~ /^triangles/) {print $i; exit}}')
    IFS='|' read -r seconds onSurfaces mib <<< "$(bakeFacts "$tmp/log")"
    echo "| $detail | $texels | ${triangles:-?} | $onSurfaces | $seconds |"
  done
} > "$tmp/growth.md"
cat "$tmp/growth.md"
/usr/bin/python3 scripts/page_table.py renderer/gi/lightmap/README.md lightmap-growth "How the bake grows" "$tmp/growth.md"
fi

if wants modes; then
export GIS_LIGHTMAP_CACHE=$tmp/cache-modes  # its own bakes, timed (the presets' medium would be read back)
{
  header lightmap.mode
  for scene in cornell_box cornell_point atrium; do
    mapfile -t flags < <(sceneFlags "$scene" | tr ' ' '\n')
    none=$(frameMs "${flags[@]}" --gi none)
    for mode in indirect all; do row "$scene" "$mode" "$none" "${flags[@]}" --preset medium --set "lightmap.mode=$mode"; done
  done
} > "$tmp/modes.md"
cat "$tmp/modes.md"
/usr/bin/python3 scripts/page_table.py renderer/gi/lightmap/README.md lightmap-modes "What a bake of all the light buys" "$tmp/modes.md"
fi
