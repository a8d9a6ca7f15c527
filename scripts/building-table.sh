#!/usr/bin/env bash
# The real-scale tables of the GI method pages (issue #39), in one sitting: each method at its
# defaults and its `realtime` preset
#   - against Cycles at 256x256: the atrium courtyard (../shared/assets/reference) and
#     builtin:building's corridor and hall (assets/reference/building): PSNR (sRGB) and the mean
#     radiance over the reference's;
#   - builtin:building's leak number: the closed room's mean over the corridor's (0 in truth);
#   - against our path tracer at 128x128, single models under the default sun and sky: the mean
#     radiance over the path tracer's.
# Writes each method's table between the "scale-table" markers of renderer/gi/METHOD/README.md.
#
# Usage (project root, after a build): bash scripts/building-table.sh [BIN (build/gisandbox)]
# Environment: METHODS (vct,sdf,probes,hddagi), PRESETS (default,realtime,path-test,environment;
# "default" = no preset; "path-test" = the defaults with the probe gather's path test switched the
# other way, for the methods that have one: the trade between leaks through walls and points no
# probe reaches; "environment" = the defaults with emitters.environment switched the other way from
# what the method does by default: the sky as a light of the direct pass or through the method's
# own rays; a KEY=VALUE: the defaults with that one parameter set).
set -euo pipefail
case ${1:-} in -h|--help) sed -n '2,/^set -e/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0 ;; esac
cd "$(dirname "$0")/.."
bin=${1:-build/gisandbox}
methods=${METHODS:-vct,sdf,probes,hddagi}
presets=${PRESETS:-default,realtime,path-test,environment}
shared=../shared/assets
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

source scripts/table_lib.sh

atrium=(--scene "$shared/reference/scenes/atrium/atrium.gltf" --background 0.35,0.45,0.6)
models=("$shared/gltf/BoxTextured/glTF/BoxTextured.gltf" "$shared/gltf/BoxVertexColors/BoxVertexColors.glb"
        "$shared/gltf/DamagedHelmet/glTF/DamagedHelmet.gltf" "$shared/gltf/VulkanSamplesAssets/teapot.gltf"
        "$shared/gltf/VulkanSamplesAssets/torusknot.gltf")
for i in "${!models[@]}"; do render "$tmp/model$i-pt.exr" --scene "${models[$i]}" --gi pathtrace --size 128x128; done

pathTestKey() {  # METHOD -> its path-test key, or nothing
  case $1 in probes|hddagi) echo "$1.path-test" ;; sdf) echo "sdf.probe-path-test" ;; esac
}
environmentFlipped() {  # METHOD -> emitters.environment set against what the method does under auto
  case $("$bin" methods "$1" 2>/dev/null | sed -n 's/^emitters.environment=auto: the environment is //p') in
    "a light"*) echo "emitters.environment=false" ;;
    "not a light"*) echo "emitters.environment=true" ;;
    *) echo "$(basename "$0" .sh): \`methods $1\` no longer says what emitters.environment=auto does" >&2; exit 1 ;;
  esac
}
pathTestFlipped() {  # METHOD -> the row's flags and label: the key set to the other value than its default
  local key now
  key=$(pathTestKey "$1")
  now=$("$bin" methods "$1" 2>/dev/null | awk -v k="$key" '$1 == k && !v {v = $5} END {print v}')
  if [ "$now" = true ]; then echo "--set $key=false"; else echo "--set $key=true"; fi
}

gl=$("$bin" render --scene builtin:cornell --size 8x8 --out "$tmp/gl.png" -v 2>&1 | sed -n 's/^GL_RENDERER: //p')
for m in ${methods//,/ }; do
  {
    echo "\`scripts/building-table.sh\`, $(date -u +%Y-%m-%d), ${gl:-unknown GL renderer}. PSNR (sRGB) / mean radiance over"
    echo "the reference's: Cycles for the atrium and the building (256x256), our path tracer for the single"
    echo "models (128x128, default sun and sky). Leak: the building's closed room over its corridor (0 in truth)."
    echo
    echo "| preset | atrium | building corridor | building hall | leak | BoxTextured | BoxVertexColors | DamagedHelmet | teapot | torusknot |"
    echo "|---|---|---|---|---|---|---|---|---|---|"
    for p in ${presets//,/ }; do
      flags=(--gi "$m")
      if [ "$p" = path-test ]; then
        [ -n "$(pathTestKey "$m")" ] || continue
        read -r -a extra <<< "$(pathTestFlipped "$m")"
        flags+=("${extra[@]}"); p="\`${extra[1]}\`"
      elif [ "$p" = environment ]; then
        p=$(environmentFlipped "$m")
        flags+=(--set "$p"); p="\`$p\`"
      elif [[ $p == *=* ]]; then
        flags+=(--set "$p"); p="\`$p\`"
      elif [ "$p" != default ]; then
        flags+=(--preset "$p")
      fi
      render "$tmp/atrium.exr" "${atrium[@]}" "${flags[@]}" --size 256x256
      render "$tmp/corridor.exr" --scene builtin:building --camera 0 "${flags[@]}" --size 256x256
      render "$tmp/hall.exr" --scene builtin:building --camera 1 "${flags[@]}" --size 256x256
      render "$tmp/closed.exr" --scene builtin:building --camera 2 "${flags[@]}" --size 256x256
      row="| $p | $(compare "$tmp/atrium.exr" "$shared/reference/refs/atrium/full.exr")"
      row+=" | $(compare "$tmp/corridor.exr" assets/reference/building/corridor/full.exr)"
      row+=" | $(compare "$tmp/hall.exr" assets/reference/building/hall/full.exr)"
      row+=" | $(ratio "$tmp/closed.exr" "$tmp/corridor.exr")"
      for i in "${!models[@]}"; do
        render "$tmp/model.exr" --scene "${models[$i]}" "${flags[@]}" --size 128x128
        row+=" | $(ratio "$tmp/model.exr" "$tmp/model$i-pt.exr")"
      done
      echo "$row |"
    done
  } > "$tmp/$m.md"
  python3 scripts/page_table.py "renderer/gi/$m/README.md" scale-table \
    "At real scale: a building, a courtyard, single models" "$tmp/$m.md"
  echo "wrote the table into renderer/gi/$m/README.md" >&2
done
