#!/usr/bin/env bash
# VCT's sky rays (vct.sky-rays, issue #39) in one sitting: for each count of rays per cone, at the
# defaults and at the `realtime` preset,
#   - against Cycles at 256x256: the atrium courtyard, builtin:building's corridor and hall (PSNR
#     sRGB / mean radiance over the reference's), and cornell_point (PSNR: the Cornell-scale figure);
#   - builtin:building's leak number: the closed room's mean over the corridor's (0 in truth);
#   - DamagedHelmet under the default sun and sky against our path tracer (128x128): mean ratio;
#   - the corridor's GPU ms at 256x256 for the trace and the sky filter (medians of every pass
#     executed each frame, --rerun-settled).
# Writes the table between the "sky-table" markers of renderer/gi/vct/README.md.
#
# Usage (project root, after a build): bash scripts/vct-sky-table.sh [BIN (build/gisandbox)]
# Environment: RAYS (0,1,2,4,8: the counts at the defaults), REALTIME_RAYS (0,1,4).
set -euo pipefail
case ${1:-} in -h|--help) sed -n '2,/^set -e/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0 ;; esac
cd "$(dirname "$0")/.."
bin=${1:-build/gisandbox}
rays=${RAYS:-0,1,2,4,8}
realtimeRays=${REALTIME_RAYS:-0,1,4}
shared=../shared/assets
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

source scripts/table_lib.sh

helmet=(--scene "$shared/gltf/DamagedHelmet/glTF/DamagedHelmet.gltf")
render "$tmp/helmet-pt.exr" "${helmet[@]}" --gi pathtrace --size 128x128

gpuMs() {  # flags... -> "trace ms / filter ms" of the corridor at 256x256
  timeout 1800 "$bin" render --scene builtin:building --camera 0 --size 256x256 --timings --rerun-settled --frames 4 \
    --warmup 1 --out "$tmp/timed.png" "$@" 2>/dev/null |
    awk '$1 == "trace" {t = $2} $1 == "sky" && $2 == "filter" {f = $3} END {printf "%.0f / %s", t, f == "" ? "-" : sprintf("%.0f", f)}'
}

row() {  # label flags... -> one table row
  local label=$1; shift
  render "$tmp/helmet.exr" "${helmet[@]}" --gi vct "$@" --size 128x128
  cyclesRenders --gi vct "$@"
  echo "| $label$(cyclesColumns) | $(ratio "$tmp/helmet.exr" "$tmp/helmet-pt.exr") | $(gpuMs --gi vct "$@") |"
}

gl=$("$bin" render --scene builtin:cornell --size 8x8 --out "$tmp/gl.png" -v 2>&1 | sed -n 's/^GL_RENDERER: //p')
{
  echo "\`scripts/vct-sky-table.sh\`, $(date -u +%Y-%m-%d), ${gl:-unknown GL renderer}. PSNR (sRGB) / mean radiance over"
  echo "the reference's: Cycles at 256x256 (cornell_point: PSNR alone); DamagedHelmet: mean over our path"
  echo "tracer's (128x128, default sun and sky). Leak: the building's closed room over its corridor (0 in"
  echo "truth). GPU ms: the corridor at 256x256, trace / sky filter (medians, every pass run each frame)."
  echo
  echo "| \`vct.sky-rays\` | atrium | building corridor | building hall | leak | cornell_point | DamagedHelmet | GPU ms trace / filter |"
  echo "|---|---|---|---|---|---|---|---|"
  for n in ${rays//,/ }; do row "$n" --set "vct.sky-rays=$n"; done
  for n in ${realtimeRays//,/ }; do row "$n, \`realtime\`" --preset realtime --set "vct.sky-rays=$n"; done
} > "$tmp/table.md"
python3 scripts/page_table.py renderer/gi/vct/README.md sky-table "Sky rays, measured" "$tmp/table.md"
echo "wrote the table into renderer/gi/vct/README.md" >&2
