#!/usr/bin/env bash
# VCT's presets on cornell_point at 256x256: what each adds over `--gi none` in wall-clock ms per
# frame (glFinish), measured in pairs A B A B in one sitting, and its PSNR (sRGB) against Cycles.
# Every pass runs every frame (--rerun-settled): a settled static view would cost nothing, and the
# figure is what a moving camera pays. Prints the Markdown table of renderer/gi/vct/README.md.
#   bash scripts/vct-realtime-table.sh [build/gisandbox]
# FRAMES / WARMUP (default 40 / 10) set the frames per timing run; PRESETS the presets measured.
# The image scored is the last timing run's, after FRAMES frames: at least framesToConverge.
set -euo pipefail
cd "$(dirname "$0")/.."
bin=${1:-build/gisandbox}
frames=${FRAMES:-40}
warmup=${WARMUP:-10}
presets=${PRESETS:-low medium high realtime}
scene=../shared/assets/reference/scenes/cornell_point/cornell_point.gltf
reference=../shared/assets/reference/refs/cornell_point/full.exr
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

wall() {  # out.exr, flags... -> median wall ms per frame after warm-up
  local out=$1; shift
  "$bin" render --scene "$scene" --size 256x256 --timings --rerun-settled --frames "$frames" --warmup "$warmup" --out "$out" "$@" \
    2>/dev/null | awk '$1 == "wall" {print $2}'
}
psnr() { "$bin" diff "$1" "$reference" | awk '/^PSNR sRGB/ {print $3}'; }
scale() {  # preset -> the trace scale its description names (presets without one trace every pixel)
  "$bin" methods vct | awk -v p="$1" '$1 == "preset" && $2 == p {
    s = 1; if (match($0, /trace scale [124]/)) s = substr($0, RSTART + 12, 1); print s }'
}

echo "| preset | trace-scale | \`--gi none\` wall ms | vct wall ms | added over none (ms) | PSNR sRGB vs Cycles (dB) |"
echo "|---|---|---|---|---|---|"
for p in $presets; do
  n1=$(wall "$tmp/none.exr" --gi none)
  v1=$(wall "$tmp/vct.exr" --gi vct --preset "$p")
  n2=$(wall "$tmp/none.exr" --gi none)
  v2=$(wall "$tmp/vct.exr" --gi vct --preset "$p")
  awk -v p="$p" -v s="$(scale "$p")" -v n1="$n1" -v n2="$n2" -v v1="$v1" -v v2="$v2" -v q="$(psnr "$tmp/vct.exr")" 'BEGIN {
    n = (n1 + n2) / 2; v = (v1 + v2) / 2
    printf "| %s | %s | %.1f | %.1f | %+.1f | %.2f |\n", p, s, n, v, v - n, q }'
done
