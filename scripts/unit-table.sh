#!/usr/bin/env bash
# The building at every unit of length (issue #39): builtin:building exported to glTF and scaled
# by 1e-3 and 1e3 under a new root node (camera clip planes, punctual lights' ranges and point and
# spot intensities with it, as the scale-invariance tests do), its corridor (camera 0) rendered by
# each method at its defaults and compared with the corridor's Cycles reference at 256x256: PSNR
# (sRGB) / mean radiance over the reference's. The three columns should agree: light transport has
# no unit of length, so neither may a method.
# Writes the table between the "unit-table" markers of docs/hardening.md.
#
# Usage (project root, after a build): bash scripts/unit-table.sh [BIN (build/gisandbox)]
# Environment: METHODS (vct,sdf,probes,hddagi).
set -euo pipefail
case ${1:-} in -h|--help) sed -n '2,/^set -e/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0 ;; esac
cd "$(dirname "$0")/.."
bin=${1:-build/gisandbox}
methods=${METHODS:-vct,sdf,probes,hddagi}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

source scripts/table_lib.sh

"$bin" export --scene builtin:building --out "$tmp/x1.gltf" > "$tmp/export.log" 2>&1 ||
  { cat "$tmp/export.log" >&2; exit 1; }
# The sky is not in the file; export names it ("... a sky of radiance (R, G, B) ...").
sky=$(sed -n 's/.*sky of radiance (\([^)]*\)).*/\1/p' "$tmp/export.log" | tr -d ' ')
[ -n "$sky" ] || { echo "unit-table: export named no sky:" >&2; cat "$tmp/export.log" >&2; exit 1; }
for scale in 1e-3 1e3; do
  /usr/bin/python3 - "$tmp/x1.gltf" "$tmp/x$scale.gltf" "$scale" <<'PY'
import json, sys
src, dst, s = sys.argv[1], sys.argv[2], float(sys.argv[3])
g = json.load(open(src))
scene = g["scenes"][g.get("scene", 0)]
g["nodes"].append({"name": "unit", "scale": [s, s, s], "children": scene["nodes"]})
scene["nodes"] = [len(g["nodes"]) - 1]
for c in g.get("cameras", []):
    p = c.get("perspective") or c.get("orthographic")
    for key in ("znear", "zfar"):
        if key in p: p[key] *= s
    for key in ("xmag", "ymag"):
        if key in p: p[key] *= s
for light in g.get("extensions", {}).get("KHR_lights_punctual", {}).get("lights", []):
    if "range" in light: light["range"] *= s
    if light.get("type") in ("point", "spot"): light["intensity"] = light.get("intensity", 1.0) * s * s
json.dump(g, open(dst, "w"))
PY
done

gl=$("$bin" render --scene builtin:cornell --size 8x8 --out "$tmp/gl.png" -v 2>&1 | sed -n 's/^GL_RENDERER: //p')
{
  echo "\`scripts/unit-table.sh\`, $(date -u +%Y-%m-%d), ${gl:-unknown GL renderer}. builtin:building's corridor"
  echo "(camera 0) exported to glTF and scaled under a root node, each method at its defaults, against"
  echo "Cycles at 256x256: PSNR (sRGB) / mean radiance over the reference's."
  echo
  echo "| method | x1 | x1e-3 | x1e3 |"
  echo "|---|---|---|---|"
  for m in ${methods//,/ }; do
    row="| \`$m\`"
    for scale in 1 1e-3 1e3; do
      render "$tmp/corridor.exr" --scene "$tmp/x$scale.gltf" --camera 0 --background "$sky" --gi "$m" --size 256x256
      row+=" | $(compare "$tmp/corridor.exr" assets/reference/building/corridor/full.exr)"
    done
    echo "$row |"
  done
} > "$tmp/table.md"
python3 scripts/page_table.py docs/hardening.md unit-table "The building at every unit of length" "$tmp/table.md"
cat "$tmp/table.md"
