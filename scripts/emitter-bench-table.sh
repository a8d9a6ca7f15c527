#!/usr/bin/env bash
# Speed against error of the two emitter modes on the emitter-lit Cornell box: one bench run with
# --emitters lights,gi (each cell once per mode, one path-traced reference), printed as the
# Markdown table of renderer/emitters/README.md.
#   bash scripts/emitter-bench-table.sh [build/gisandbox]
# METHODS / PRESETS / SIZE (default none,vct,sdf,probes / medium / 128x128) choose the cells, OUT the
# bench's directory (default a temporary one; its cache keeps the reference between runs). GPU ms
# is per frame, or the total to converge for progressive cells (marked).
set -euo pipefail
cd "$(dirname "$0")/.."
bin=${1:-build/gisandbox}
out=${OUT:-$(mktemp -d)}
"$bin" bench --scenes builtin:cornell-area --methods "${METHODS:-none,vct,sdf,probes}" \
  --presets "${PRESETS:-medium}" --size "${SIZE:-128x128}" --emitters lights,gi --out-dir "$out" >&2
python3 - "$out/bench.json" <<'PY'
import json, sys
rows = json.load(open(sys.argv[1]))["results"]
by = {(r["method"], r["preset"], r.get("emitters", "")): r for r in rows}
def ms(r):  # progressive cells (ReSTIR's accumulation, probe updates): the total to converge
    return "%.1f%s" % (r["gpu_ms"], " (to converge)" if r.get("gpu_ms_to_converge") else "")
print("| method | preset | GPU ms lights | GPU ms gi | PSNR sRGB lights | PSNR sRGB gi | FLIP lights | FLIP gi |")
print("|---|---|---|---|---|---|---|---|")
for key in dict.fromkeys((r["method"], r["preset"]) for r in rows):
    l, g = by[key + ("lights",)], by[key + ("gi",)]
    print("| %s | %s | %s | %s | %.2f | %.2f | %.3f | %.3f |" % (
        key[0], key[1], ms(l), ms(g), l["psnr_srgb"], g["psnr_srgb"], l["flip"], g["flip"]))
PY
