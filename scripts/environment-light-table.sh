#!/usr/bin/env bash
# The environment as a light of the direct pass (emitters.environment, issue #40), measured in one
# sitting: every deferred method with it off and on, against Cycles at 256x256,
#   - builtin:atrium lit by assets/environments/sky_sun.hdr alone (assets/reference/atrium_sky_sun):
#     the whole image, and the mean over the surfaces the map's sun does not reach (the path
#     tracer's direct light there, box-blurred, under a quarter of its 90th percentile) over Cycles'
#     mean there;
#   - the atrium courtyard under its sun and a uniform sky (../shared/assets/reference/refs/atrium);
#   - the direct pass's GPU ms per frame on the map-lit atrium (--timings, every pass every frame).
# Writes the table between the "environment-light-table" markers of renderer/emitters/README.md.
#
# Usage (project root, after a build): bash scripts/environment-light-table.sh [BIN (build/gisandbox)]
# Environment: METHODS (none,ssao,vct,sdf,probes,hddagi).
set -euo pipefail
case ${1:-} in -h|--help) sed -n '2,/^set -e/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0 ;; esac
cd "$(dirname "$0")/.."
bin=${1:-build/gisandbox}
methods=${METHODS:-none,ssao,vct,sdf,probes,hddagi}
shared=../shared/assets/reference
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

source scripts/table_lib.sh
/usr/bin/python3 -c 'import PIL' 2>/dev/null || { echo "environment-light-table.sh: needs Debian's python3-pil (apt-get install python3-pil)" >&2; exit 1; }

maplit=(--scene builtin:atrium --environment assets/environments/sky_sun.hdr --lighting none --size 256x256)
atrium=(--scene "$shared/scenes/atrium/atrium.gltf" --background 0.35,0.45,0.6 --size 256x256)
# The shade mask: diff leaves out pixels whose red is >= 128, so every pixel the sun reaches (and the sky).
render "$tmp/direct.png" "${maplit[@]}" --gi pathtrace --view direct --tonemap linear --set pathtrace.spp=64 \
  --set emitters.environment=true
/usr/bin/python3 - "$tmp/direct.png" "$tmp/shade.png" <<'PY'
import sys
from PIL import Image, ImageFilter
d = Image.open(sys.argv[1]).convert("L").filter(ImageFilter.BoxBlur(2))  # the path tracer's noise out
values = sorted(d.getdata())
bright = values[len(values) * 9 // 10]
m = d.point(lambda v: 0 if 0 < v < bright / 4 else 255)
Image.merge("RGB", (m, m, m)).save(sys.argv[2])
PY

gl=$("$bin" render --scene builtin:cornell --size 8x8 --out "$tmp/gl.png" -v 2>&1 | sed -n 's/^GL_RENDERER: //p')
{
  echo "\`scripts/environment-light-table.sh\`, $(date -u +%Y-%m-%d), ${gl:-unknown GL renderer}. PSNR (sRGB) / mean radiance"
  echo "over Cycles' (256x256). Shade: the mean over the surfaces the map's sun does not reach, over Cycles' there."
  echo "Direct ms: the direct pass's (ReSTIR) GPU time per frame on the map-lit atrium (llvmpipe: a ratio, not a budget)."
  echo
  echo "| method | \`emitters.environment\` | atrium, sky_sun.hdr alone | its shade | atrium courtyard | direct ms |"
  echo "|---|---|---|---|---|---|"
  for m in ${methods//,/ }; do
    for e in false true; do
      flags=(--gi "$m" --set "emitters.environment=$e")
      render "$tmp/maplit.exr" "${maplit[@]}" "${flags[@]}"
      render "$tmp/atrium.exr" "${atrium[@]}" "${flags[@]}"
      ms=$(passMs emitters 20 "${maplit[@]}" "${flags[@]}")
      row="| $m | $e | $(compare "$tmp/maplit.exr" assets/reference/atrium_sky_sun/full.exr)"
      row+=" | $(ratio "$tmp/maplit.exr" assets/reference/atrium_sky_sun/full.exr --mask "$tmp/shade.png")"
      row+=" | $(compare "$tmp/atrium.exr" "$shared/refs/atrium/full.exr")"
      echo "$row | ${ms:-none} |"
    done
  done
} > "$tmp/table.md"
cat "$tmp/table.md"
/usr/bin/python3 scripts/page_table.py renderer/emitters/README.md environment-light-table \
  "The environment as a light, measured" "$tmp/table.md"
