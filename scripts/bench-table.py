#!/usr/bin/env python3
"""Print a bench.csv (written by `gisandbox bench`) as the markdown table docs/bench.md shows:
one row per scene and method, the presets side by side in the CSV's order: the steady frame, the
median frame while converging, after a camera cut and after a light edit the frame from which the
image stopped changing (of the frames run until final) and the GPU ms until then, memory, and the
error of the first and the final frame.

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
    need = {"scene", "method", "preset", "gpu_ms", "converge_frames", "converge_frame_gpu_ms",
            "converge_settled_frames", "converge_settled_gpu_ms", "edit_frames", "edit_settled_frames",
            "edit_settled_gpu_ms", "gpu_bytes", "first_flip", "flip", "rmse", "ao_rmse"}
    if not rows or not need <= set(rows[0]):
        sys.exit("bench-table.py: %s is not a bench.csv of this version (needs columns %s)" % (path, ", ".join(sorted(need))))
    groups = {}
    for r in rows:
        groups.setdefault((r["scene"], r["method"]), []).append(r)
    presets = ", ".join(dict.fromkeys(r["preset"] for r in rows))
    print("| scene | method (%s) | steady ms | converging ms | after a cut: settled at frame (of) / ms "
          "| after a light edit: settled at frame (of) / ms | GPU MiB | FLIP frame 1 | FLIP final | RMSE final | AO RMSE |" % presets)
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for (scene, method), g in groups.items():
        join = lambda key, fmt: ", ".join(fmt(r[key]) if r[key] != "" else "-" for r in g)
        settled = lambda k: ", ".join("%s (%s) / %s" % (r[k + "_settled_frames"], r[k + "_frames"],
                                                        ms(r[k + "_settled_gpu_ms"]))
                                    if r[k + "_frames"] != "" else "-" for r in g)
        ao = join("ao_rmse", lambda v: "%.3f" % float(v)) if all(r["ao_rmse"] for r in g) else ""
        print("| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s |" % (
            scene, method, join("gpu_ms", ms), join("converge_frame_gpu_ms", ms),
            settled("converge"), settled("edit"),
            join("gpu_bytes", lambda v: "%.1f" % (float(v) / 2**20)), join("first_flip", lambda v: "%.3f" % float(v)),
            join("flip", lambda v: "%.3f" % float(v)), join("rmse", lambda v: "%.4f" % float(v)), ao))


if __name__ == "__main__":
    main()
