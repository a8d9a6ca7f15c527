#!/usr/bin/env bash
# SDF GI's hit threshold at building scale (issue #39) in one sitting: for each `sdf.hit-threshold`
# (in cells of the cascade a ray marches in; it holds for the pixels' and the probes' rays, while
# the gather's path test keeps half a cell),
#   - against Cycles at 256x256: the atrium courtyard, builtin:building's corridor and hall (PSNR
#     sRGB / mean radiance over the reference's), and cornell_point (PSNR: the Cornell-scale figure);
#   - builtin:building's leak number: the closed room's mean over the corridor's (0 in truth);
#   - the sky through the atrium's arches: lit by the sky alone (`--lighting none`), the mean over
#     the left wing's upper loggia (LOGGIA) of SDF GI's own one-bounce rays (`sdf.diffuse=rays`:
#     what they see of the sky) over the path tracer's direct light there;
#   - SDF GI's probes in the building and the corridor's GPU ms for them and for the gather.
# Writes the table between the "threshold-table" markers of renderer/gi/sdf/README.md.
#
# Usage (project root, after a build): bash scripts/sdf-threshold-table.sh [BIN (build/gisandbox)]
# Environment: THRESHOLDS (1,0.5,0.25,0.1); LOGGIA (x0,y0,x1,y1: the 256x256 atrium image's pixels of
# the upper loggia's back wall on the left, 48,88,64,104).
set -euo pipefail
case ${1:-} in -h|--help) sed -n '2,/^set -e/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0 ;; esac
cd "$(dirname "$0")/.."
bin=${1:-build/gisandbox}
thresholds=${THRESHOLDS:-1,0.5,0.25,0.1}
loggia=${LOGGIA:-48,88,64,104}
[[ $loggia =~ ^[0-9]+,[0-9]+,[0-9]+,[0-9]+$ ]] ||
  { echo "sdf-threshold-table.sh: LOGGIA is x0,y0,x1,y1 (pixels of the 256x256 image), not '$loggia'" >&2; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
/usr/bin/python3 -c 'import PIL' 2>/dev/null || { echo "sdf-threshold-table.sh: needs Debian's python3-pil (apt-get install python3-pil)" >&2; exit 1; }

source scripts/table_lib.sh

# The loggia as a `diff --mask` (red: left out).
/usr/bin/python3 - "$tmp/loggia.png" "$loggia" <<'PY'
import sys
from PIL import Image, ImageDraw
mask = Image.new("RGB", (256, 256), (255, 0, 0))
ImageDraw.Draw(mask).rectangle([int(v) for v in sys.argv[2].split(",")], fill=(0, 0, 0))
mask.save(sys.argv[1])
PY
skyOnly=(--scene ../shared/assets/reference/scenes/atrium/atrium.gltf --background 0.35,0.45,0.6 --lighting none
         --size 256x256)
render "$tmp/sky-pt.exr" "${skyOnly[@]}" --gi pathtrace --set pathtrace.bounces=0 --set pathtrace.spp=64

gl=$("$bin" render --scene builtin:cornell --size 8x8 --out "$tmp/gl.png" -v 2>&1 | sed -n 's/^GL_RENDERER: //p')
{
  echo "\`scripts/sdf-threshold-table.sh\`, $(date -u +%Y-%m-%d), ${gl:-unknown GL renderer}. PSNR (sRGB) / mean radiance over"
  echo "Cycles' at 256x256 (cornell_point: PSNR alone). Leak: the building's closed room over its corridor"
  echo "(0 in truth). Loggia sky: the atrium lit by its sky alone, SDF GI's one-bounce rays over the path"
  echo "tracer's direct light on the upper loggia's back wall (pixels $loggia). Probes: the building's, every"
  echo "cascade; GPU ms: the corridor at 256x256, every probe updated / the gather, every pass run each frame."
  echo
  echo "| \`sdf.hit-threshold\` | atrium | building corridor | building hall | leak | cornell_point | loggia sky | probes | GPU ms probes | GPU ms gather |"
  echo "|---|---|---|---|---|---|---|---|---|---|"
  for t in ${thresholds//,/ }; do
    cyclesRenders --gi sdf --set "sdf.hit-threshold=$t"
    render "$tmp/sky-rays.exr" "${skyOnly[@]}" --gi sdf --set sdf.diffuse=rays --set "sdf.hit-threshold=$t"
    echo "| $t$(cyclesColumns) | $(ratio "$tmp/sky-rays.exr" "$tmp/sky-pt.exr" --mask "$tmp/loggia.png") | $(sdfCosts --gi sdf --set "sdf.hit-threshold=$t") |"
  done
} > "$tmp/table.md"
python3 scripts/page_table.py renderer/gi/sdf/README.md threshold-table \
  "What the hit threshold trades at building scale" "$tmp/table.md"
echo "wrote the table into renderer/gi/sdf/README.md" >&2
