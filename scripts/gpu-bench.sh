#!/usr/bin/env bash
# One-shot GPU benchmark at 1920x1080: every benchmarked method and preset on the Cornell boxes and
# the atrium, with GPU and wall-clock ms, memory and error against a path-traced reference, and the
# fly-through of the atrium (scripts/flythrough-table.sh).
#
#   here (no GPU needed):   bash scripts/gpu-bench.sh pack      # builds, packs .gpuz/gpu.tar.xz
#   on the GPU machine:     bash scripts/gpu-bench.sh run OUT   # EGL, headless; writes OUT/bench/, OUT/flythrough/
#
# The lent NVIDIA machine has no package registry and no display: `pack` bundles the binary and its
# libraries here (../shared/tools/gpu-bundle) and compresses them, since the device tool carries at
# most 64 MiB with the working tree; carry .gpuz, and `run` unpacks it, sources .gpu/env.sh and reads
# shaders from the repo. Sized to finish in under 8 minutes on one H100/H200: 256-spp references
# (cached under OUT/bench/cache), 20 frames per measurement. The scenes are benchmarked one more at a
# time into the same folder, the finished cells being cached no-ops, so a run cut short by the lease
# still leaves a bench.csv of the scenes it finished.
# SIZE, SPP and BIN (a binary to use instead of the bundle's) shrink it for a check on this machine:
#   SIZE=64x64 SPP=4 BIN=build/gisandbox bash scripts/gpu-bench.sh run /tmp/gpu-bench-check
set -euo pipefail
cd "$(dirname "$0")/.."
case ${1:-} in
  pack)
    bash scripts/build.sh
    ../shared/tools/gpu-bundle build/gisandbox
    # Within the device tool's 64 MiB: no debug information, no Cycles references (the bench renders
    # its own), the rest xz-compressed.
    strip .gpu/bin/gisandbox
    rm -rf .gpu/shared
    grep -qx '/.gpuz/' .git/info/exclude || echo '/.gpuz/' >> .git/info/exclude
    mkdir -p .gpuz
    tar -cf - .gpu | xz -T0 -6 > .gpuz/gpu.tar.xz
    echo "packed .gpuz/gpu.tar.xz ($(du -h .gpuz/gpu.tar.xz | cut -f1)): now run the device tool with carry [\".gpuz\"] and: bash scripts/gpu-bench.sh run \$OUT"
    ;;
  run)
    out=${2:?usage: gpu-bench.sh run OUT_DIR}
    size=${SIZE:-1920x1080}
    bin=${BIN:-}
    if [ -z "$bin" ]; then
      [ -d .gpu ] || tar -xJf .gpuz/gpu.tar.xz
      # shellcheck disable=SC1091
      source .gpu/env.sh
      bin=.gpu/bin/gisandbox
    fi
    export GIS_SHADER_DIR=$PWD/shaders
    "$bin" info --scene builtin:cornell --size "$size" --backend egl | tail -4
    scenes=""
    for scene in builtin:cornell builtin:cornell-area builtin:atrium; do
      scenes=${scenes:+$scenes,}$scene
      time "$bin" bench --backend egl --size "$size" --frames 20 --warmup 5 --reference-spp "${SPP:-256}" \
        --scenes "$scenes" --out-dir "$out/bench"
    done
    # Camera motion: the scripted fly-through of the atrium (60 frames), median and worst frame and
    # what a cascade move costs, per method and preset (the table of docs/bench.md).
    SIZE=$size bash scripts/flythrough-table.sh "$bin" "$out/flythrough" --backend egl
    # Path tracer throughput against triangle count on the atrium (detail 1, 4, 10: ~14k to 1.2M).
    for d in 1 4 10; do
      "$bin" render --backend egl --scene "builtin:atrium?detail=$d" --size "$size" --gi pathtrace --spp 16 \
        --timings --frames 4 --warmup 0 --out "$out/atrium_d$d.png" | grep -E "pathtrace|rays|wall" | sed "s/^/detail $d: /"
    done
    ;;
  *)
    sed -n '2,18p' "$0"
    exit 2
    ;;
esac
