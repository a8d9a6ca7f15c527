#!/usr/bin/env bash
# Speed against error of the two emitter modes on the emitter-lit Cornell box: one bench run with
# --emitters lights,gi (each cell once per mode, one path-traced reference), printed as the
# Markdown table of renderer/emitters/README.md.
#   bash scripts/emitter-bench-table.sh [build/gisandbox]
# METHODS / PRESETS / SIZE (default none,vct,sdf,probes / medium / 128x128) choose the cells, OUT the
# bench's directory (default a temporary one; its cache keeps the reference between runs). Each GPU
# figure is a frame's cost (bench's chart: the dearer of a converging and a steady frame) and, after
# the slash, the total from a camera cut until final.
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
def ms(r):  # a frame / from a cut until final
    return "%.1f / %.0f" % (max(r["gpu_ms"], r["converge"]["frame_gpu_ms"]), r["converge"]["gpu_ms"])
print("| method | preset | GPU ms lights (frame / to final) | GPU ms gi (frame / to final) | PSNR sRGB lights "
      "| PSNR sRGB gi | FLIP lights | FLIP gi |")
print("|---|---|---|---|---|---|---|---|")
for key in dict.fromkeys((r["method"], r["preset"]) for r in rows):
    l, g = by[key + ("lights",)], by[key + ("gi",)]
    print("| %s | %s | %s | %s | %.2f | %.2f | %.3f | %.3f |" % (
        key[0], key[1], ms(l), ms(g), l["psnr_srgb"], g["psnr_srgb"], l["flip"], g["flip"]))
PY
