#!/usr/bin/env bash
# Our frame against Godot 3.2.3's on the same Cornell box (cornell_point, 256x256), measured side by
# side in one sitting, as wall-clock ms per frame (ours with glFinish; Godot's includes presenting
# under Xvfb). Prints a Markdown table with the ratios. Needs godot3 and xvfb (Debian packages):
#   apt-get install -y --no-install-recommends godot3 xvfb
# Usage (project root, after a build): bash scripts/godot-compare.sh [build/gisandbox]
set -euo pipefail
cd "$(dirname "$0")/.."
bin=${1:-build/gisandbox}
peer=../shared/peers/godot3-cornell
scene=../shared/assets/reference/scenes/cornell_point/cornell_point.gltf
command -v godot3 >/dev/null || { echo "godot3 is not installed (apt-get install godot3 xvfb)" >&2; exit 1; }

godot() {  # variant -> median ms per frame
  bash "$peer/run.sh" "$1" | sed -n 's/.*FRAME_MS[^0-9]*\([0-9.]*\).*/\1/p' | head -1
}
ours() {  # flags -> median wall ms per frame
  "$bin" render --scene "$scene" --size 256x256 --timings --rerun-settled --frames 40 --warmup 10 --out /tmp/gis_compare.png "$@" |
    awk '$1 == "wall" {print $2}'
}
g0="" o0=""  # the direct frames: what each variant adds is measured over them
row() {  # label, godot variant, our flags...
  local label=$1 variant=$2; shift 2
  local g o
  g=$(godot "$variant"); o=$(ours "$@")
  [ -n "$g0" ] || { g0=$g; o0=$o; }
  awk -v l="$label" -v v="$variant" -v g="$g" -v f="$*" -v o="$o" -v g0="$g0" -v o0="$o0" 'BEGIN {
    added = (g > g0 && v != "direct") ? sprintf("+%.1f / +%.1f = %.2f", o - o0, g - g0, (o - o0) / (g - g0)) : "";
    printf "| %s | %s: %.1f | `%s`: %.1f | %.2f | %s |\n", l, v, g, f, o, o / g, added }'
}
echo "| frame | Godot 3.2.3 GLES3 (wall ms) | gisandbox (wall ms, glFinish) | ours / Godot | added over direct: ours / Godot |"
echo "|---|---|---|---|---|"
row "direct light, one shadowed point light" direct --gi none
row "+ SSAO (Godot default / our medium: GTAO 3 slices x 4 steps)" ssao --gi ssao --preset medium
row "+ SSAO (our low: GTAO 3x4 at half resolution)" ssao --gi ssao --preset low
row "+ SSAO (our previous medium: hemisphere 16x4)" ssao --gi ssao --preset hemisphere-medium
row "voxel GI (GIProbe 128 / our vct high)" gi128 --gi vct --preset high
row "voxel GI (GIProbe 64 / our vct medium)" gi64 --gi vct --preset medium
# Godot 3 has no SDF or probe GI: GIProbe is the GI it has, so both compare with it.
row "SDF GI (GIProbe 128 / our sdf high)" gi128 --gi sdf --preset high
row "SDF GI (GIProbe 64 / our sdf medium)" gi64 --gi sdf --preset medium
row "probe GI (GIProbe 128 / our probes high)" gi128 --gi probes --preset high
row "probe GI (GIProbe 64 / our probes medium)" gi64 --gi probes --preset medium
