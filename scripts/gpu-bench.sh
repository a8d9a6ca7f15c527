#!/usr/bin/env bash
# One-shot GPU benchmark at 1920x1080: every benchmarked method and preset on the Cornell boxes and
# the atrium, with GPU and wall-clock ms, memory and error against a path-traced reference, and the
# fly-through of the atrium (scripts/flythrough-table.sh).
#
#   here (no GPU needed):   bash scripts/gpu-bench.sh pack      # builds, packs .gpu/ (gpu-bundle)
#   on the GPU machine:     bash scripts/gpu-bench.sh run OUT   # EGL, headless; writes OUT/bench/, OUT/flythrough/
#
# The lent NVIDIA machine has no package registry and no display: `pack` bundles the binary and its
# libraries here (../shared/tools/gpu-bundle); the device tool carries .gpu with the working tree,
# and `run` sources .gpu/env.sh and reads shaders from the repo. Sized to finish in under 8 minutes
# on one H100/H200: 256-spp references (cached under OUT/bench/cache), 20 frames per measurement.
set -euo pipefail
cd "$(dirname "$0")/.."
case ${1:-} in
  pack)
    bash scripts/build.sh
    ../shared/tools/gpu-bundle build/gisandbox
    echo "packed .gpu/: now run the device tool with carry [\".gpu\"] and: bash scripts/gpu-bench.sh run \$OUT"
    ;;
  run)
    out=${2:?usage: gpu-bench.sh run OUT_DIR}
    # shellcheck disable=SC1091
    source .gpu/env.sh
    export GIS_SHADER_DIR=$PWD/shaders
    bin=.gpu/bin/gisandbox
    "$bin" info --scene builtin:cornell --size 1920x1080 --backend egl | tail -4
    time "$bin" bench --backend egl --size 1920x1080 --frames 20 --warmup 5 --reference-spp 256 \
      --scenes builtin:cornell,builtin:cornell-area,builtin:atrium --out-dir "$out/bench"
    # Camera motion: the scripted fly-through of the atrium (60 frames), median and worst frame and
    # what a cascade move costs, per method and preset (the table of docs/bench.md).
    SIZE=1920x1080 bash scripts/flythrough-table.sh "$bin" "$out/flythrough" --backend egl
    # Path tracer throughput against triangle count on the atrium (detail 1, 4, 10: ~14k to 1.2M).
    for d in 1 4 10; do
      "$bin" render --backend egl --scene "builtin:atrium?detail=$d" --size 1920x1080 --gi pathtrace --spp 16 \
        --timings --frames 4 --warmup 0 --out "$out/atrium_d$d.png" | grep -E "pathtrace|rays|wall" | sed "s/^/detail $d: /"
    done
    ;;
  *)
    sed -n '2,12p' "$0"
    exit 2
    ;;
esac
