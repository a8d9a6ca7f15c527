#!/usr/bin/env bash
# The side-by-side tables of renderer/gi/hddagi/README.md: `sdf`, `probes` and `hddagi` at the same
# presets on the same scenes, in one sitting. Two parts:
#  1. gis_gi_tests' Hddagi.MeasureSideBySide (GIS_MEASURE=hddagi), once per preset: PSNR against
#     the path tracer, the leak number, cost to converge, a static frame, a light edit, memory;
#  2. scripts/flythrough-table.sh: the atrium fly-through, median and worst frame, cascade moves.
# The tables replace what lies between the README's "hddagi-table" markers.
#
# Usage (project root, after a build): bash scripts/hddagi-table.sh [BUILD_DIR (build)]
# Environment: PRESETS (medium,realtime), SIZE (the fly-through's, 256x256).
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
presets=${PRESETS:-medium,realtime}
page=renderer/gi/hddagi/README.md
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
{
  echo "Static scenes: ${build}/tests/gis_gi_tests at 96x96 against the 16-bounce, 64-spp path tracer;"
  gl=$("$build/gisandbox" render --scene builtin:cornell --size 8x8 --out "$out/gl.png" -v 2>&1 | sed -n 's/^GL_RENDERER: //p')
  echo "$(date -u +%Y-%m-%d), ${gl:-unknown GL renderer}, $(nproc) cores."
  echo
  echo "| method/preset | PSNR cornell | PSNR cornell-area | PSNR atrium | leak number | to converge (GI GPU ms, frames) | static frame re-rendered (GI GPU ms) | light edit: first frame, to converge again | MiB held |"
  echo "|---|---|---|---|---|---|---|---|---|"
  for p in ${presets//,/ }; do
    GIS_MEASURE=hddagi HDDAGI_PRESET=$p "$build/tests/gis_gi_tests" --gtest_filter=Hddagi.MeasureSideBySide \
      | sed -n 's/^HDDAGI-SIDE \(.*\)$/| \1 |/p'
  done
  echo
  echo "Moving camera: \`bench --flythrough\` on builtin:atrium at ${SIZE:-256x256} (scripts/flythrough-table.sh;"
  echo "a cascade move is a frame that voxelized: rebuilt for sdf, scrolled for hddagi)."
  echo
  METHODS=sdf,probes,hddagi PRESETS=$presets bash scripts/flythrough-table.sh "$build/gisandbox" "$out/fly"
} > "$out/table.md"
python3 - "$page" "$out/table.md" <<'PY'
import sys
page, table = sys.argv[1], open(sys.argv[2]).read()
text = open(page).read()
begin, end = "<!-- hddagi-table begin -->\n", "<!-- hddagi-table end -->"
head, rest = text.split(begin)
tail = rest.split(end)[1]
open(page, "w").write(head + begin + table + end + tail)
PY
echo "wrote the tables into $page" >&2
