#!/usr/bin/env bash
# Whether the viewer holds its frame budget (issue #42), for docs/viewer.md: for each method at its
# default preset, `gisandbox view` under Xvfb (1280x720 window: an 860x720 view) runs a scripted
# orbit (ORBIT steps of 3 degrees, one a frame) and then waits until the view has converged, with
# --frame-log. The table: the pane's full frame, the median and worst window frame while the camera
# moves, the median while the method converges at the reduced scale, the worst while it climbs back
# to full scale, and the seconds from the orbit's end to the settled view. Writes its table between
# the "viewer-budget" markers of docs/viewer.md (PAGE=- prints it).
#
# Usage (project root, after a build): bash scripts/viewer-budget-table.sh [BIN (build/gisandbox)]
# Environment: METHODS (none,ssao,vct,sdf,probes,hddagi,pathtrace), ORBIT (30), BUDGET (0: the
# renderer's default), SCENE (builtin:cornell), PAGE (docs/viewer.md).
set -euo pipefail
case ${1:-} in -h|--help) sed -n '2,/^set -e/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0 ;; esac
cd "$(dirname "$0")/.."
bin=$(realpath "${1:-build/gisandbox}")
methods=${METHODS:-none,ssao,vct,sdf,probes,hddagi,pathtrace}
orbit=${ORBIT:-30}
budget=${BUDGET:-0}
scene=${SCENE:-builtin:cornell}
page=${PAGE:-docs/viewer.md}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
command -v xvfb-run > /dev/null || { echo "viewer-budget-table: needs xvfb-run (apt-get install xvfb)" >&2; exit 1; }

gl=$("$bin" render --scene builtin:cornell --size 8x8 --out "$tmp/gl.png" -v 2>&1 | sed -n 's/^GL_RENDERER: //p')
for m in ${methods//,/ }; do
  {
    echo "frame-budget $budget"
    echo "method 0 $m"
    echo "wait 3"
    echo "sleep 0.1"
    echo "# orbit"
    for ((i = 0; i < orbit; ++i)); do echo "camera orbit 3 0"; echo "wait 1"; done
    echo "converge"
    echo "quit"
  } > "$tmp/$m.txt"
  timeout 1800 xvfb-run -a -s "-screen 0 1280x720x24" "$bin" view --scene "$scene" --size 1280x720 \
    --script "$tmp/$m.txt" --frame-log "$tmp/$m.tsv" --screenshot-dir "$tmp" > "$tmp/$m.log" 2>&1 ||
    { echo "viewer-budget-table: $m failed:" >&2; tail -3 "$tmp/$m.log" >&2; exit 1; }
  echo "viewer-budget-table: $m done" >&2
done

python3 - "$tmp" "$methods" "$(date -u +%Y-%m-%d)" "${gl:-unknown GL renderer}" "$orbit" "$budget" > "$tmp/table.md" <<'PY'
import statistics, sys
tmp, methods, day, gl, orbit, budget = sys.argv[1:]
print(f"Measured {day} on {gl} under Xvfb (`bash scripts/viewer-budget-table.sh`): `builtin:cornell`, an")
print(f"860x720 view, frame budget {'the default' if budget == '0' else budget + ' ms'}, an orbit of {orbit} steps of 3 degrees then")
print("`converge`. Window frames in ms (wall clock: the panel and the swap included); GPU ms are the")
print("passes' timings that arrived in the frame; the full frame is the pane's estimate the budget is")
print("held against (the median over the orbit).\n")
print("| method | full frame GPU ms | scale while moving | moving: window ms median, worst | moving: GPU ms median "
      "| converging reduced: window ms median | climbing: worst window ms | s to settled after the orbit |")
print("|---|---|---|---|---|---|---|---|")
for m in methods.split(","):
    rows = [l.rstrip("\n").split("\t") for l in open(f"{tmp}/{m}.tsv")][1:]
    # seconds, window ms, GPU ms, then pane 0's scale, full frame GPU ms, moving, status
    rows = [(float(r[0]), float(r[1]), float(r[2]), float(r[3]), float(r[4]), r[5] == "1", r[6] if len(r) > 6 else "")
            for r in rows]
    moving = [r for r in rows if r[5]]
    converging = [r for r in rows if "converging" in r[6]]
    climbing = [r for r in rows if "refining" in r[6]]
    full = statistics.median([r[4] for r in moving]) if moving else max(r[4] for r in rows)
    fmt = lambda xs: "%.0f, %.0f" % (statistics.median(xs), max(xs)) if xs else "-"
    scale = statistics.median([r[3] for r in moving]) if moving else 1.0
    print(f"| {m} | {full:.0f} | {'1' if scale == 1.0 else '1/%d' % round(1 / scale)} | {fmt([r[1] for r in moving])} | "
          f"{statistics.median([r[2] for r in moving]) if moving else 0:.0f} | "
          f"{'%.0f' % statistics.median([r[1] for r in converging]) if converging else '-'} | "
          f"{'%.0f' % max(r[1] for r in climbing) if climbing else '-'} | {rows[-1][0] - moving[-1][0] if moving else 0:.1f} |")
PY
if [[ $page == - ]]; then cat "$tmp/table.md"
else python3 scripts/page_table.py "$page" viewer-budget "The frame budget, measured" "$tmp/table.md"; echo "wrote $page" >&2
fi
