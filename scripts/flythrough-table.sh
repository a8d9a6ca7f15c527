#!/usr/bin/env bash
# Camera motion measured: `bench --flythrough` on builtin:atrium (the scripted path of
# renderer/camera_path.h, 60 frames after a warm-up frame), then its bench.csv as the Markdown
# table of docs/bench.md: per method and preset the median and worst GPU ms per frame, how many
# frames moved (rebuilt) a cascade, and the median frame with a cascade move against one without.
#
# Usage (project root, after a build):
#   bash scripts/flythrough-table.sh [BIN] [OUT_DIR (bench/flythrough)] [more bench flags, e.g. --backend egl]
# Environment: SIZE (256x256), METHODS (none,vct,sdf,probes), PRESETS (low,medium,high).
# The bench's own lines go to stderr, the table to stdout.
set -euo pipefail
cd "$(dirname "$0")/.."
bin=${1:-build/gisandbox}
out=${2:-bench/flythrough}   # under bench/, which git ignores
shift $(($# < 2 ? $# : 2))
"$bin" bench --flythrough --scenes builtin:atrium --size "${SIZE:-256x256}" --methods "${METHODS:-none,vct,sdf,probes}" \
  --presets "${PRESETS:-low,medium,high}" --out-dir "$out" "$@" >&2
echo "| method/preset | median ms | worst ms | frames that moved a cascade | median ms, frames that moved a cascade | median ms, the other frames |"
echo "|---|---|---|---|---|---|"
awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) col[$i] = i; next }
  function ms(v) { return v == "" ? "-" : sprintf("%.1f", v) }
  { printf "| %s/%s | %s | %s | %d of %d | %s | %s |\n", $col["method"], $col["preset"], ms($col["gpu_ms"]),
      ms($col["fly_worst_ms"]), $col["fly_move_frames"], $col["fly_frames"], ms($col["fly_move_ms"]), ms($col["fly_still_ms"]) }' \
  "$out/bench.csv"
