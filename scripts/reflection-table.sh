#!/usr/bin/env bash
# The reflection tables of the probe-based method pages (issue #40: a specular term of every
# method's own), in one sitting: each method at its defaults, with its `reflection=environment`
# (the prefiltered sky alone, what the lighting pass gave before) and at its `realtime` preset,
#   - builtin:mirror against Cycles (assets/reference/mirror, 256x256): the whole image and its two
#     metal spheres alone (the pixels whose G-buffer metallic is 1): PSNR (sRGB) / mean radiance
#     over the reference's;
#   - DamagedHelmet under a white sky against Cycles (../shared/assets/reference/refs/DamagedHelmet_sky);
#   - builtin:atrium lit by assets/environments/sky_sun.hdr alone against Cycles
#     (assets/reference/atrium_sky_sun): the map's sun casts no shadow yet but the path tracer's;
#   - cornell_point against Cycles (its diffuse figure must not move);
#   - the reflection step's GPU ms per frame on builtin:mirror (--timings, every pass each frame).
# Writes each method's table between the "reflection-table" markers of renderer/gi/METHOD/README.md.
#
# Usage (project root, after a build; needs `apt-get install python3-pil` for the spheres' mask):
#   bash scripts/reflection-table.sh [BIN (build/gisandbox)]
# Environment: METHODS (vct,sdf,probes,hddagi).
set -euo pipefail
case ${1:-} in -h|--help) sed -n '2,/^set -e/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0 ;; esac
cd "$(dirname "$0")/.."
bin=${1:-build/gisandbox}
methods=${METHODS:-vct,sdf,probes,hddagi}
shared=../shared/assets/reference
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

source scripts/table_lib.sh
/usr/bin/python3 -c 'import PIL' 2>/dev/null || { echo "reflection-table.sh: needs Debian's python3-pil (apt-get install python3-pil)" >&2; exit 1; }

mirror=(--scene builtin:mirror --size 256x256)
helmet=(--scene ../shared/assets/gltf/DamagedHelmet/glTF/DamagedHelmet.gltf --camera-pos 0 0 3.2 --look-at 0 0 0
        --fov 40 --background 1 --lighting scene --size 256x256)  # Cycles' setup: a white sky and no other light
cornell=(--scene "$shared/scenes/cornell_point/cornell_point.gltf" --size 256x256)
maplit=(--scene builtin:atrium --environment assets/environments/sky_sun.hdr --lighting none --size 256x256)
# The spheres' mask: diff leaves out pixels whose red is >= 128, so every pixel but the metals'.
render "$tmp/material.png" "${mirror[@]}" --gi none --view gbuffer.material --tonemap linear
/usr/bin/python3 - "$tmp/material.png" "$tmp/mask.png" <<'PY'
import sys
from PIL import Image
m = Image.open(sys.argv[1]).convert("RGB")
r = m.getchannel("R").point(lambda v: 0 if v >= 128 else 255)
Image.merge("RGB", (r, r, r)).save(sys.argv[2])
PY

gl=$("$bin" render --scene builtin:cornell --size 8x8 --out "$tmp/gl.png" -v 2>&1 | sed -n 's/^GL_RENDERER: //p')
for m in ${methods//,/ }; do
  hasKey=$("$bin" methods "$m" 2>/dev/null | awk -v k="$m.reflection" '$1 == k {found = 1} END {if (found) print "yes"}')
  {
    echo "\`scripts/reflection-table.sh\`, $(date -u +%Y-%m-%d), ${gl:-unknown GL renderer}. PSNR (sRGB) / mean radiance over"
    echo "Cycles' at 256x256. Spheres: builtin:mirror's two metal spheres alone (the mirror and the rough metal)."
    echo "Reflection ms: the reflection step's GPU time per frame on builtin:mirror (llvmpipe: a ratio, not a budget)."
    echo
    echo "| row | builtin:mirror | its spheres | DamagedHelmet, white sky | atrium, sky_sun.hdr alone | cornell_point | reflection ms |"
    echo "|---|---|---|---|---|---|---|"
    rows=(default realtime)
    [ -n "$hasKey" ] && rows=(default environment realtime)
    for p in "${rows[@]}"; do
      flags=(--gi "$m"); label=$p
      case $p in
        environment) flags+=(--set "$m.reflection=environment"); label="\`$m.reflection=environment\`" ;;
        realtime) flags+=(--preset realtime) ;;
      esac
      render "$tmp/mirror.exr" "${mirror[@]}" "${flags[@]}"
      render "$tmp/helmet.exr" "${helmet[@]}" "${flags[@]}"
      render "$tmp/cornell.exr" "${cornell[@]}" "${flags[@]}"
      render "$tmp/maplit.exr" "${maplit[@]}" "${flags[@]}"
      ms=$(passMs reflection 30 "${mirror[@]}" "${flags[@]}")
      row="| $label | $(compare "$tmp/mirror.exr" assets/reference/mirror/full.exr)"
      row+=" | $(compare "$tmp/mirror.exr" assets/reference/mirror/full.exr --mask "$tmp/mask.png")"
      row+=" | $(compare "$tmp/helmet.exr" "$shared/refs/DamagedHelmet_sky/full.exr")"
      row+=" | $(compare "$tmp/maplit.exr" assets/reference/atrium_sky_sun/full.exr)"
      row+=" | $(compare "$tmp/cornell.exr" "$shared/refs/cornell_point/full.exr")"
      echo "$row | ${ms:-none} |"
    done
  } > "$tmp/$m.md"
  cat "$tmp/$m.md"
  /usr/bin/python3 scripts/page_table.py "renderer/gi/$m/README.md" reflection-table "Reflections, measured" "$tmp/$m.md"
done
