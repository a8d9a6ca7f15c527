#!/usr/bin/env bash
# Where builtin:building's hall loses its light (issue #39), bounce by bounce: the hall (camera 1,
# lit only by what comes in through three doorways) at 256x256, each method with its first bounce
# alone and with every bounce (its defaults): the image's mean radiance over Cycles'
# (assets/reference/building/hall/full.exr); our path tracer at one, two and every bounce says how
# much of the light each bounce carries. Whole images, not the indirect views: the path tracer and
# vct count the sky's light on a surface as indirect, Cycles' passes and the methods that take the
# environment as a light (emitters.environment) as direct.
# Writes the table between the "hall-bounce-table" markers of renderer/gi/hddagi/README.md.
#
# Usage (project root, after a build): bash scripts/hall-bounce-table.sh [BIN (build/gisandbox)]
set -euo pipefail
case ${1:-} in -h|--help) sed -n '2,/^set -e/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0 ;; esac
cd "$(dirname "$0")/.."
bin=${1:-build/gisandbox}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

source scripts/table_lib.sh

reference=assets/reference/building/hall/full.exr
hall() {  # NAME flags...: renders the hall into NAME.exr, in this shell, so that a failed render ends the script
  local name=$1; shift
  render "$tmp/$name.exr" --scene builtin:building --camera 1 --size 256x256 "$@"
}
mean() { ratio "$tmp/$1.exr" "$reference"; }  # NAME -> its mean over Cycles'
# METHOD -> the flag that leaves its first bounce alone, or nothing where it has none to set
firstBounceFlag() {
  case $1 in vct) echo "--set vct.bounces=1" ;; probes|hddagi) echo "--set $1.multibounce=false" ;; esac
}
ptBounces=$("$bin" methods pathtrace | awk '$1 == "pathtrace.bounces" {print $6}')

hall pt1 --gi pathtrace --spp 64 --max-bounces 1
hall pt2 --gi pathtrace --spp 64 --max-bounces 2
hall pt --gi pathtrace --spp 64
methods=(vct sdf probes hddagi)
for m in "${methods[@]}"; do
  read -r -a first <<< "$(firstBounceFlag "$m")"
  [ ${#first[@]} -eq 0 ] || hall "$m-first" --gi "$m" "${first[@]}"
  hall "$m" --gi "$m"
done

gl=$("$bin" render --scene builtin:cornell --size 8x8 --out "$tmp/gl.png" -v 2>&1 | sed -n 's/^GL_RENDERER: //p')
{
  echo "\`scripts/hall-bounce-table.sh\`, $(date -u +%Y-%m-%d), ${gl:-unknown GL renderer}. \`builtin:building\`'s hall"
  echo "(camera 1), 256x256: the image's mean radiance over Cycles', with the first bounce alone and with"
  echo "every bounce (the defaults; the path tracer: $ptBounces bounces, 64 samples per pixel). Much of Cycles' mean"
  echo "is the sky seen through the doorways, which every row has."
  echo
  echo "| method | first bounce | every bounce |"
  echo "|---|---|---|"
  echo "| pathtrace | $(mean pt1) | $(mean pt) (two bounces: $(mean pt2)) |"
  for m in "${methods[@]}"; do
    one="-"
    [ ! -f "$tmp/$m-first.exr" ] || one=$(mean "$m-first")
    echo "| $m | $one | $(mean "$m") |"
  done
} > "$tmp/table.md"
python3 scripts/page_table.py renderer/gi/hddagi/README.md hall-bounce-table \
  "The hall's light, bounce by bounce" "$tmp/table.md"
echo "wrote the table into renderer/gi/hddagi/README.md" >&2
