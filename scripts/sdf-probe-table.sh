#!/usr/bin/env bash
# SDFGI's probe spacing and rays per probe at building scale (issue #39) in one sitting: for each
# row (a spacing and a ray count, and the `realtime` preset at the defaults),
#   - against Cycles at 256x256: the atrium courtyard, builtin:building's corridor and hall (PSNR
#     sRGB / mean radiance over the reference's), and cornell_point (PSNR: the Cornell-scale figure);
#   - builtin:building's leak number: the closed room's mean over the corridor's (0 in truth);
#   - the probes the building holds (every cascade), and the corridor's GPU ms at 256x256 for the
#     probes (trace and blends) and for the gather (trace and filter): medians of every pass
#     executed each frame (--rerun-settled), so the probes' cost is that of updating every one.
# Writes the table between the "probe-table" markers of renderer/gi/sdf/README.md.
#
# Usage (project root, after a build): bash scripts/sdf-probe-table.sh [BIN (build/gisandbox)]
# Environment: ROWS (spacing:rays pairs, "default" and "realtime"; "0.25:128,0.125:128,default,realtime").
set -euo pipefail
case ${1:-} in -h|--help) sed -n '2,/^set -e/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0 ;; esac
cd "$(dirname "$0")/.."
bin=${1:-build/gisandbox}
rows=${ROWS:-0.25:128,0.125:128,default,realtime}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

source scripts/table_lib.sh

row() {  # label flags... -> one table row
  local label=$1; shift
  cyclesRenders --gi sdf "$@"
  echo "| $label$(cyclesColumns) | $(sdfCosts --gi sdf "$@") |"
}

gl=$("$bin" render --scene builtin:cornell --size 8x8 --out "$tmp/gl.png" -v 2>&1 | sed -n 's/^GL_RENDERER: //p')
{
  echo "\`scripts/sdf-probe-table.sh\`, $(date -u +%Y-%m-%d), ${gl:-unknown GL renderer}. PSNR (sRGB) / mean radiance over"
  echo "Cycles' at 256x256 (cornell_point: PSNR alone). Leak: the building's closed room over its corridor"
  echo "(0 in truth). Probes: the building's, every cascade. GPU ms: the corridor at 256x256, every probe"
  echo "updated (trace and blends) / the gather (trace and filter); medians, every pass run each frame."
  echo
  echo "| spacing / rays per probe | atrium | building corridor | building hall | leak | cornell_point | probes | GPU ms probes | GPU ms gather |"
  echo "|---|---|---|---|---|---|---|---|---|"
  for r in ${rows//,/ }; do
    case $r in
      default) row "defaults ($("$bin" methods sdf | awk '$1 == "sdf.probe-spacing" || $1 == "sdf.probe-rays" {for (i = 2; i < NF; ++i) if ($i == "default") printf "%s%s", s, $(i + 1); s = " / "}'))" ;;
      realtime) row "\`realtime\`" --preset realtime ;;
      *:*) row "${r%%:*} / ${r##*:}" --set "sdf.probe-spacing=${r%%:*}" --set "sdf.probe-rays=${r##*:}" ;;
      *) echo "sdf-probe-table: a row is spacing:rays, default or realtime, not '$r'" >&2; exit 1 ;;
    esac
  done
} > "$tmp/table.md"
python3 scripts/page_table.py renderer/gi/sdf/README.md probe-table \
  "Probe spacing at building scale" "$tmp/table.md"
echo "wrote the table into renderer/gi/sdf/README.md" >&2
