#!/usr/bin/env python3
"""Print a bench.csv (written by `gisandbox bench`) as the markdown table docs/bench.md shows:
one row per scene and method, the presets side by side in the CSV's order: the steady frame, the
median frame while converging, the frames and GPU ms from a camera cut until final, the frames
after a light edit, memory, and the error of the first and the final frame.

    python3 scripts/bench-table.py OUT_DIR/bench.csv
"""
import argparse
import csv
import sys


def ms(v):
    # Three significant digits, whole milliseconds from 1000 on (no exponent notation).
    x = float(v)
    return str(round(x)) if x >= 1000 else "%.3g" % x


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("csv", help="a bench.csv written by gisandbox bench")
    path = parser.parse_args().csv
    try:
        with open(path, newline="") as f:
            rows = list(csv.DictReader(f))
    except OSError as e:
        sys.exit("bench-table.py: %s: %s" % (path, e.strerror))
    need = {"scene", "method", "preset", "gpu_ms", "converge_frames", "converge_gpu_ms", "converge_frame_gpu_ms",
            "edit_frames", "edit_gpu_ms", "gpu_bytes", "first_flip", "flip", "rmse", "ao_rmse"}
    if not rows or not need <= set(rows[0]):
        sys.exit("bench-table.py: %s is not a bench.csv of this version (needs columns %s)" % (path, ", ".join(sorted(need))))
    groups = {}
    for r in rows:
        groups.setdefault((r["scene"], r["method"]), []).append(r)
    presets = ", ".join(dict.fromkeys(r["preset"] for r in rows))
    print("| scene | method (%s) | steady ms | converging ms | after a cut: frames / ms to final "
          "| after a light edit: frames / ms | GPU MiB | FLIP frame 1 | FLIP final | RMSE final | AO RMSE |" % presets)
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for (scene, method), g in groups.items():
        join = lambda key, fmt: ", ".join(fmt(r[key]) if r[key] != "" else "-" for r in g)
        pair = lambda n, t: ", ".join("%s / %s" % (r[n], ms(r[t])) if r[n] != "" else "-" for r in g)
        ao = join("ao_rmse", lambda v: "%.3f" % float(v)) if all(r["ao_rmse"] for r in g) else ""
        print("| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |" % (
            scene, method, join("gpu_ms", ms), join("converge_frame_gpu_ms", ms),
            pair("converge_frames", "converge_gpu_ms"), pair("edit_frames", "edit_gpu_ms"),
            join("gpu_bytes", lambda v: "%.1f" % (float(v) / 2**20)), join("first_flip", lambda v: "%.3f" % float(v)),
            join("flip", lambda v: "%.3f" % float(v)), join("rmse", lambda v: "%.4f" % float(v)), ao))


if __name__ == "__main__":
    main()
