#!/usr/bin/env bash
# Our frame against Godot 3.2.3's on the same Cornell box (cornell_point, 256x256), measured side by
# side in one sitting, as wall-clock ms per frame (ours with glFinish; Godot's includes presenting
# under Xvfb), with our image's PSNR (sRGB) against the Cycles reference. Prints a Markdown table
# with the ratios. Godot is measured before and after ours (both figures printed, the ratios use
# their mean): two figures far apart mean the machine was not quiet. Needs godot3 and xvfb (Debian):
#   apt-get install -y --no-install-recommends godot3 xvfb
# Usage (project root, after a build): bash scripts/godot-compare.sh [build/gisandbox]
# ONLY=sdf,probes keeps the direct row and the rows of those methods (a shorter sitting).
set -euo pipefail
cd "$(dirname "$0")/.."
bin=${1:-build/gisandbox}
peer=../shared/peers/godot3-cornell
scene=../shared/assets/reference/scenes/cornell_point/cornell_point.gltf
cycles=../shared/assets/reference/refs/cornell_point/full.exr
command -v godot3 >/dev/null || { echo "godot3 is not installed (apt-get install godot3 xvfb)" >&2; exit 1; }
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

# The rows: label | Godot variant | our flags. The first is the direct frame: what every other row
# adds is measured over it, on each side.
rows=(
  "direct light, one shadowed point light|direct|--gi none"
  "+ SSAO (Godot default / our medium: GTAO 3 slices x 4 steps)|ssao|--gi ssao --preset medium"
  "+ SSAO (our low: GTAO 3x4 at half resolution)|ssao|--gi ssao --preset low"
  "+ SSAO (our previous medium: hemisphere 16x4)|ssao|--gi ssao --preset hemisphere-medium"
  "voxel GI (GIProbe 128 / our vct high)|gi128|--gi vct --preset high"
  "voxel GI (GIProbe 64 / our vct medium)|gi64|--gi vct --preset medium"
  "voxel GI (GIProbe 64 / our vct realtime)|gi64|--gi vct --preset realtime"
  # Godot 3 has no SDF or probe GI: GIProbe is the GI it has, so both compare with it.
  "SDF GI (GIProbe 128 / our sdf high)|gi128|--gi sdf --preset high"
  "SDF GI (GIProbe 64 / our sdf medium)|gi64|--gi sdf --preset medium"
  "SDF GI (GIProbe 64 / our sdf realtime)|gi64|--gi sdf --preset realtime"
  "probe GI (GIProbe 128 / our probes high)|gi128|--gi probes --preset high"
  "probe GI (GIProbe 64 / our probes medium)|gi64|--gi probes --preset medium"
  "probe GI (GIProbe 64 / our probes realtime)|gi64|--gi probes --preset realtime"
)
variants="direct ssao gi64 gi128"
if [ -n "${ONLY:-}" ]; then
  kept=("${rows[0]}")
  for row in "${rows[@]:1}"; do
    for m in ${ONLY//,/ }; do [[ "$row" == *"--gi $m "* ]] && kept+=("$row"); done
  done
  rows=("${kept[@]}")
  variants="direct gi64 gi128"
fi

godot() {  # variant -> median ms per frame
  bash "$peer/run.sh" "$1" | sed -n 's/.*FRAME_MS[^0-9]*\([0-9.]*\).*/\1/p' | head -1
}
has_preset() {  # method preset: does this build have it? (grep reads it all: -q would exit early
  # and, under pipefail, the writer's SIGPIPE would read as "no such preset")
  "$bin" methods "$1" | grep "^  preset $2 " >/dev/null
}
# Every pass runs every frame (--rerun-settled), as Godot re-renders a static view: the cost a
# moving camera pays, not the nothing a settled static view costs.
render() {  # out.exr flags... -> render --timings' output
  local exr=$1; shift
  "$bin" render --scene "$scene" --size 256x256 --timings --rerun-settled --out "$exr" "$@"
}
# Ours, for one row: "wall_ms psnr_srgb updates" (updates: probe updates to converge, or -).
# A progressive pass (probes, SDFGI's probes) is measured after it converged: a first run renders
# until it has (no --frames) and counts its updates (--timings' "for N samples"), the second
# leaves that many frames out of the median.
ours() {
  local exr="$out/ours.exr" log="$out/ours.log" updates=- wall psnr
  render "$exr" --frames 40 --warmup 10 "$@" >"$log"
  if grep -q ' for [0-9]* samples' "$log"; then
    render "$exr" "$@" >"$log"
    updates=$(sed -n 's/.* for \([0-9]*\) samples.*/\1/p' "$log" | head -1)
    render "$exr" --frames $((updates + 40)) --warmup $((updates + 10)) "$@" >"$log"
  fi
  wall=$(awk '$1 == "wall" {print $2}' "$log")
  psnr=$("$bin" diff "$exr" "$cycles" --json | sed -n 's/.*"psnr_srgb_db": *\([0-9.]*\).*/\1/p')
  echo "$wall $psnr $updates"
}

declare -A before after
for v in $variants; do before[$v]=$(godot "$v"); done
results=()
for row in "${rows[@]}"; do
  IFS='|' read -r label variant flags <<<"$row"
  read -r -a f <<<"$flags"
  if [ "${f[2]:-}" = --preset ] && ! has_preset "${f[1]}" "${f[3]}"; then
    results+=("no-preset")
  else
    results+=("$(ours "${f[@]}")")
  fi
done
for v in $variants; do after[$v]=$(godot "$v"); done

echo "| frame | Godot 3.2.3 GLES3 (wall ms, before / after ours) | gisandbox (wall ms, glFinish) | PSNR sRGB vs Cycles | probe updates to converge | ours / Godot | added over direct: ours / Godot |"
echo "|---|---|---|---|---|---|---|"
g0="" o0=""
for i in "${!rows[@]}"; do
  IFS='|' read -r label variant flags <<<"${rows[$i]}"
  gb=${before[$variant]} ga=${after[$variant]}
  if [ "${results[$i]}" = no-preset ]; then
    # shellcheck disable=SC2016 # the backticks are Markdown
    printf '| %s | %s: %.1f / %.1f | `%s`: no such preset | | | | |\n' "$label" "$variant" "$gb" "$ga" "$flags"
    continue
  fi
  read -r o psnr updates <<<"${results[$i]}"
  [ -n "$g0" ] || { g0=$(awk -v a="$gb" -v b="$ga" 'BEGIN {print (a + b) / 2}'); o0=$o; }
  awk -v l="$label" -v v="$variant" -v gb="$gb" -v ga="$ga" -v f="$flags" -v o="$o" -v p="$psnr" -v u="$updates" \
      -v g0="$g0" -v o0="$o0" 'BEGIN {
    g = (gb + ga) / 2;
    added = (g > g0 && v != "direct") ? sprintf("+%.1f / +%.1f = %.2f", o - o0, g - g0, (o - o0) / (g - g0)) : "";
    printf "| %s | %s: %.1f / %.1f | `%s`: %.1f | %s | %s | %.2f | %s |\n", l, v, gb, ga, f, o,
           (p == "" ? "" : sprintf("%.1f dB", p)), (u == "-" ? "" : u), o / g, added }'
done
