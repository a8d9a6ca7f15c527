#!/usr/bin/env bash
# The emitter-lit glTF files next to the path tracer (renderer/emitters/README.md): each scene at
# SIZE (default 256x256) under every method of METHODS (default vct sdf probes, at their defaults,
# --emitters lights) and the path tracer (SPP samples, default 64, 16 bounces), written to
# screenshots/emitters_SCENE_METHOD.png; prints the README's Markdown table of them.
#   bash scripts/emitter-screenshots.sh [build/gisandbox]
set -euo pipefail
cd "$(dirname "$0")/.."
bin=${1:-build/gisandbox}
size=${SIZE:-256x256}
methods=${METHODS:-vct sdf probes}
spp=${SPP:-64}
declare -A scenes=([cornellbox]=../shared/assets/gltf/nvpro_CornellBox/cornellBox.gltf
                   [helmet]=../shared/assets/gltf/DamagedHelmet/glTF/DamagedHelmet.gltf)
header="| scene |"; rule="|---|"
for m in $methods pathtrace; do header+=" $m |"; rule+="---|"; done
echo "$header"; echo "$rule"
for name in cornellbox helmet; do
  row="| $name |"
  for m in $methods pathtrace; do
    out=screenshots/emitters_${name}_${m}.png
    extra=()
    [ "$m" = pathtrace ] && extra=(--set "pathtrace.spp=$spp")
    "$bin" render --scene "${scenes[$name]}" --size "$size" --gi "$m" "${extra[@]}" --out "$out" >&2
    row+=" ![$name $m](../../$out) |"
  done
  echo "$row"
done
