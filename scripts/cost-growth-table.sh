#!/usr/bin/env bash
# How each method's frame cost grows (issue #42), for docs/bench.md: the `realtime` presets of the
# GI methods that have one (and `none` at medium, the rasterized floor) against pixels (cornell,
# 128^2 .. 1024^2), triangles (builtin:atrium?detail=D), emissive triangles
# (builtin:cornell-area?emitter-tiles=K: 2 K^2 triangles of one light) and scene extent (a 2 m box
# to a 40 m building), with the exponent b of a least-squares fit ms = a x^b per row. Each point
# is `render --timings --rerun-settled --frames FRAMES` from a cut: the median wall-clock ms of a
# frame after WARMUP (on llvmpipe the GPU is the CPU, so wall is the cost; every pass executed,
# as a frame costs while the method converges). Writes its table between the "cost-growth" markers.
#
# Usage (project root, after a build): bash scripts/cost-growth-table.sh [BIN (build/gisandbox)]
# Environment: METHODS (none,vct,sdf,probes,hddagi), FRAMES (6), WARMUP (2), PAGE (docs/bench.md;
# "-" prints the table instead), POINTS (a file: the measured points are kept there, and when it
# exists already nothing is measured, the table is made from it).
set -euo pipefail
case ${1:-} in -h|--help) sed -n '2,/^set -e/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0 ;; esac
cd "$(dirname "$0")/.."
bin=${1:-build/gisandbox}
methods=${METHODS:-none,vct,sdf,probes,hddagi}
frames=${FRAMES:-6}
warmup=${WARMUP:-2}
page=${PAGE:-docs/bench.md}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# axis, x label, scene, size: one line per point.
points() {
  for s in 128 256 512 1024; do echo "pixels|$((s * s))|builtin:cornell|${s}x$s"; done
  for d in 1 2 4 6; do echo "triangles|-|builtin:atrium?detail=$d|128x128"; done  # 8: vct's ray scene passes llvmpipe's 128 MiB storage-buffer limit
  for k in 1 4 16 71; do echo "emissive|$((2 * k * k))|builtin:cornell-area?emitter-tiles=$k|128x128"; done
  for s in cornell room atrium building; do echo "extent|-|builtin:$s|128x128"; done
}

gl=$("$bin" render --scene builtin:cornell --size 8x8 --out "$tmp/gl.png" -v 2>&1 | sed -n 's/^GL_RENDERER: //p')
points_file=${POINTS:-$tmp/points.tsv}
if [[ -s $points_file && -n ${POINTS:-} ]]; then
  echo "cost-growth-table: the points in $points_file, measured before" >&2
  gl=$(sed -n 's/^# gl: //p' "$points_file")
else
echo "# gl: ${gl:-unknown GL renderer}" > "$points_file"
while IFS='|' read -r axis x scene size; do
  if [[ $x == - ]]; then  # triangles, or the bounds' longest edge in metres, from `info`
    "$bin" info --scene "$scene" > "$tmp/info.txt" 2>&1
    if [[ $axis == triangles ]]; then x=$(sed -n 's/.* \([0-9]*\) triangles$/\1/p' "$tmp/info.txt")
    else x=$(python3 -c 'import re,sys; a,b=[list(map(float,v.split(", "))) for v in re.findall(r"\(([^)]*)\)", [l for l in open(sys.argv[1]) if l.startswith("bounds")][0])]; print(max(q-p for p,q in zip(a,b)))' "$tmp/info.txt")
    fi
  fi
  for m in ${methods//,/ }; do
    preset=realtime; [[ $m == none ]] && preset=medium
    log="$tmp/run.log"
    timeout 1800 "$bin" render --scene "$scene" --gi "$m" --preset "$preset" --size "$size" --rerun-settled \
      --timings --frames "$frames" --warmup "$warmup" --out "$tmp/out.png" > "$log" 2>&1 ||
      { echo "cost-growth-table: $m on $scene at $size failed:" >&2; tail -3 "$log" >&2; exit 1; }
    ms=$(sed -n 's/^wall  *\([0-9.]*\) .*/\1/p' "$log")
    [[ -n $ms ]] || { echo "cost-growth-table: no wall line for $m on $scene" >&2; tail -3 "$log" >&2; exit 1; }
    printf '%s\t%s\t%s\t%s\t%s\n' "$axis" "$x" "$m" "$ms" "$scene $size" >> "$points_file"
    echo "$axis $x $m/$preset: $ms ms" >&2
  done
done < <(points)
fi

python3 - "$points_file" "$(date -u +%Y-%m-%d)" "${gl:-unknown GL renderer}" "$frames" "$warmup" > "$tmp/table.md" <<'PY'
import math, sys
path, day, gl, frames, warmup = sys.argv[1:]
rows = [l.rstrip("\n").split("\t") for l in open(path) if not l.startswith("#")]
axes = [("pixels", "pixels (cornell, 128^2 .. 1024^2)"), ("triangles", "triangles (atrium, detail 1 .. 6)"),
        ("emissive", "emissive triangles (cornell-area, 2 .. 10082)"), ("extent", "extent (cornell, room, atrium, building)")]
methods = list(dict.fromkeys(r[2] for r in rows))

def fit(points):  # least squares of log ms on log x: the exponent b of ms = a x^b
    xs = [math.log(float(x)) for x, _ in points]
    ys = [math.log(float(y)) for _, y in points]
    mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
    return sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)

print(f"Measured {day} on {gl}: `bash scripts/cost-growth-table.sh`, {frames} frames from a cut, the median")
print(f"wall ms of those after {warmup}; each cell lists the ms at each point, then the exponent b of a")
print("least-squares fit ms = a x^b over them and, after the slash, the exponent between the last two")
print("points (fixed costs flatten the fit at the small end). A cell marked ** grows worse than")
print("linearly (an exponent above 1.1) in pixels or triangles.\n")
xs = {a: list(dict.fromkeys(r[1] for r in rows if r[0] == a)) for a, _ in axes}
num = lambda x: "%d" % float(x) if float(x) == int(float(x)) else "%g" % float(x)
print("| method | " + " | ".join(f"{label}: {', '.join(num(x) for x in xs[a])}" for a, label in axes) + " |")
print("|---|" + "---|" * len(axes))
for m in methods:
    cells = []
    for a, _ in axes:
        pts = [(r[1], r[3]) for r in rows if r[0] == a and r[2] == m]
        b = fit(pts) if len(pts) > 1 else float("nan")
        last = fit(pts[-2:]) if len(pts) > 1 else float("nan")
        worse = a in ("pixels", "triangles") and max(b, last) > 1.1
        cells.append(", ".join("%.3g" % float(y) for _, y in pts) + f" (b = {b:.2f} / {last:.2f}{' **' if worse else ''})")
    print(f"| {m} | " + " | ".join(cells) + " |")
PY
if [[ $page == - ]]; then cat "$tmp/table.md"
else python3 scripts/page_table.py "$page" cost-growth "How cost grows" "$tmp/table.md"; echo "wrote $page" >&2
fi
