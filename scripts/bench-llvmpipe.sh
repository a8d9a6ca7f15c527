#!/usr/bin/env bash
# The default bench on this machine, made into what docs/bench.md shows: runs `gisandbox bench`
# (both Cornell boxes, every method and preset, 128x128) into OUT, copies its CSV, charts and grids
# to screenshots/bench_*, and puts the CSV's table into docs/bench.md between its bench-table
# markers (scripts/bench-table.py, scripts/page_table.py). Run it on a quiet machine: the table is
# a timing. Every cell is measured again in this sitting (OUT/cells is emptied first); the
# references in OUT/cache are reused.
#
#   bash scripts/bench-llvmpipe.sh [OUT_DIR] [BINARY]
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-/tmp/gis-bench-llvmpipe}
bin=${2:-build/gisandbox}
rm -rf "$out/cells"
"$bin" bench --out-dir "$out"
cp "$out/bench.csv" screenshots/bench_llvmpipe.csv
for scene in cornell cornell-area; do
  for kind in chart grid quality; do cp "$out/${scene}_$kind.png" "screenshots/bench_${scene}_$kind.png"; done
done
python3 scripts/bench-table.py screenshots/bench_llvmpipe.csv > "$out/table.md"
python3 scripts/page_table.py docs/bench.md bench-table Measured "$out/table.md"
echo "wrote screenshots/bench_* and the table of docs/bench.md" >&2
