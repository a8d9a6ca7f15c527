#!/usr/bin/env bash
# What the cascade count from the view changed (renderer/volume/volume_cascades.h): the scenes
# whose count it changed at x1 (the single models whose files are not in metres), each cascaded
# method at its defaults with the count from the view (METHOD.cascade-extent=0, the default) and
# with the fixed 8 world units it replaced, against our path tracer at 128x128 under the default
# sun and sky: the mean radiance over the path tracer's and PSNR (sRGB). The cascade count each
# got is read from its `--timings` stats.
# Writes the table between the "view-count-table" markers of renderer/gi/sdf/README.md.
#
# Usage (project root, after a build): bash scripts/view-count-table.sh [BIN (build/gisandbox)]
# Environment: METHODS (sdf,probes,hddagi).
set -euo pipefail
case ${1:-} in -h|--help) sed -n '2,/^set -e/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0 ;; esac
cd "$(dirname "$0")/.."
bin=${1:-build/gisandbox}
methods=${METHODS:-sdf,probes,hddagi}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

source scripts/table_lib.sh

shared=../shared/assets/gltf
models=("$shared/VulkanSamplesAssets/teapot.gltf" "$shared/VulkanSamplesAssets/torusknot.gltf")
names=(teapot torusknot)
for i in "${!models[@]}"; do render "$tmp/pt$i.exr" --scene "${models[$i]}" --gi pathtrace --size 128x128; done
count() {  # SCENE METHOD EXTENT -> the cascade count the method's stats report ("cascade N:" lines; none: 1)
  timeout 1800 "$bin" render --scene "$1" --gi "$2" --set "$2.cascade-extent=$3" --size 32x32 --timings --frames 2 \
    --warmup 1 --out "$tmp/count.png" 2>&1 | awk '$2 == "cascade" && $3 ~ /^[0-9]+:$/ {n++} END {print n ? n : 1}'
}

gl=$("$bin" render --scene builtin:cornell --size 8x8 --out "$tmp/gl.png" -v 2>&1 | sed -n 's/^GL_RENDERER: //p')
{
  echo "\`scripts/view-count-table.sh\`, $(date -u +%Y-%m-%d), ${gl:-unknown GL renderer}. Defaults, 128x128, against"
  echo "our path tracer under the default sun and sky: cascades, mean radiance over the path tracer's, PSNR (sRGB)."
  echo
  echo "| method | model | from the view (\`cascade-extent=0\`) | 8 world units (before) |"
  echo "|---|---|---|---|"
  for m in ${methods//,/ }; do
    for i in "${!models[@]}"; do
      row="| \`$m\` | ${names[$i]}"
      for extent in 0 8; do
        render "$tmp/m.exr" --scene "${models[$i]}" --gi "$m" --set "$m.cascade-extent=$extent" --size 128x128
        n=$(count "${models[$i]}" "$m" "$extent")
        row+=" | $n: $(ratio "$tmp/m.exr" "$tmp/pt$i.exr"), $(compare "$tmp/m.exr" "$tmp/pt$i.exr" | sed 's| / .*||')"
      done
      echo "$row |"
    done
  done
} > "$tmp/table.md"
python3 scripts/page_table.py renderer/gi/sdf/README.md view-count-table \
  "What the count from the view changed" "$tmp/table.md"
cat "$tmp/table.md"
