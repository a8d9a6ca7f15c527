#!/usr/bin/env bash
# What the volume costs per cascade at Cornell scale and at building scale (issue #39), for the GI
# method pages: each cascade's cells, cell size, cube, GPU memory and the GPU ms of building it on
# the first frame (its voxelize, occupancy, flood, inject ... steps), then the method's own steps
# and its median per-frame wall-clock ms with every pass executed (`render --timings`, as bench measures).
# Cascade lines come from SceneVolume::describeCascade, step rows from --timings ("cN." per cascade).
# Writes each method's table between the "cascade-table" markers of renderer/gi/METHOD/README.md.
#
# Usage (project root, after a build): bash scripts/cascade-cost-table.sh [BIN (build/gisandbox)]
# Environment: METHODS (vct,sdf,probes,hddagi), SIZE (128), FRAMES (12).
set -euo pipefail
case ${1:-} in -h|--help) sed -n '2,/^set -e/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0 ;; esac
cd "$(dirname "$0")/.."
bin=${1:-build/gisandbox}
methods=${METHODS:-vct,sdf,probes,hddagi}
size=${SIZE:-128}
frames=${FRAMES:-12}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

gl=$("$bin" render --scene builtin:cornell --size 8x8 --out "$tmp/gl.png" -v 2>&1 | sed -n 's/^GL_RENDERER: //p')
for m in ${methods//,/ }; do
  for scene in cornell building; do
    timeout 1800 "$bin" render --scene "builtin:$scene" --camera 0 --gi "$m" --size "${size}x$size" \
      --frames "$frames" --warmup 2 --timings --out "$tmp/$scene.png" > "$tmp/$m-$scene.log" 2>&1 ||
      { echo "cascade-cost-table: $m on builtin:$scene failed:" >&2; tail -3 "$tmp/$m-$scene.log" >&2; exit 1; }
  done
  python3 - "$m" "$tmp" "$size" "$frames" "$(date -u +%Y-%m-%d)" "${gl:-unknown GL renderer}" > "$tmp/$m.md" <<'PY'
import re, sys
method, tmp, size, frames, day, gl = sys.argv[1:]
volume_steps = re.compile(r"^(voxelize|occupancy|seed|jfa\.\d+\.\d+|resolve|inject|mips|bounce|exterior|scroll)$")

def read(scene):
    """Cascade lines, first-frame ms per cascade and of the method's own steps, median frame ms."""
    cascades, build, own, total = [], {}, 0.0, None
    in_method = False
    for line in open(f"{tmp}/{method}-{scene}.log"):
        m = re.search(r"cascade (\d+): (\d+)\^3 cells of ([\d.e+-]+) \(a ([\d.e+-]+) cube.*up to ([\d.]+) MiB", line)
        if m:
            cascades.append((int(m[1]), int(m[2]), float(m[3]), float(m[4]), float(m[5])))
            continue
        if re.match(rf"^{re.escape(method)}\s", line):
            in_method = True
            continue
        step = re.match(r"^  (\S.*?)\s{2,}([\d.]+)\s+([\d.]+)", line) if in_method else None
        if step and not line.startswith("  rays"):
            name, first = step[1], float(step[3])
            c = re.match(r"^c(\d+)\.(.*)$", name)
            if c:
                build[int(c[1])] = build.get(int(c[1]), 0.0) + first
            elif volume_steps.match(name):
                build[0] = build.get(0, 0.0) + first
            else:
                own += first
            continue
        if in_method and not line.startswith("  "):
            in_method = False
        m = re.match(r"^wall\s+([\d.]+)", line)
        if m:
            total = float(m[1])
    return cascades, build, own, total

rows = []
for scene, label in (("cornell", "`builtin:cornell` (2 m)"), ("building", "`builtin:building` (43 m cube)")):
    cascades, build, own, total = read(scene)
    for i, res, cell, edge, mib in cascades:
        rows.append(f"| {label} | {i} | {res}³ | {cell:.3g} m | {edge:.3g} m | {mib:.1f} | {build.get(i, 0.0):.1f} |")
    mib_all = sum(c[4] for c in cascades)
    rows.append(f"| {label} | all | | | | {mib_all:.1f} | {sum(build.values()):.1f} "
                f"(+ {own:.1f} of the method's own steps); per frame: {total if total is not None else float('nan'):.1f} ms |")
table = (f"`scripts/cascade-cost-table.sh`, {day}, {gl}; defaults, camera 0, {size}x{size}, {frames} frames. "
         "GPU ms of the first frame, which builds every cascade (voxelize, flood, inject ... summed); the "
         "method's own steps (probes, gathers) on that frame; and the median frame's wall-clock ms (with "
         "glFinish) with every pass executed. MiB: the volume's GPU memory per cascade (the field at its peak while it is built).\n\n"
         "| scene | cascade | cells | cell | cube | MiB | first-frame GPU ms |\n|---|---|---|---|---|---|---|\n"
         + "\n".join(rows) + "\n")
print(table, end="")
PY
  python3 scripts/page_table.py "renderer/gi/$m/README.md" cascade-table \
    "What each cascade costs, in a room and in a building" "$tmp/$m.md"
  echo "wrote the table into renderer/gi/$m/README.md" >&2
done
