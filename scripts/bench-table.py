#!/usr/bin/env python3
"""Print a bench.csv (written by `gisandbox bench`) as the markdown table docs/bench.md shows:
one row per scene and method, the presets side by side in the CSV's order.

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
    need = {"scene", "method", "preset", "gpu_ms", "gpu_bytes", "flip", "rmse", "ao_rmse"}
    if not rows or not need <= set(rows[0]):
        sys.exit("bench-table.py: %s is not a bench.csv (needs columns %s)" % (path, ", ".join(sorted(need))))
    groups = {}
    for r in rows:
        groups.setdefault((r["scene"], r["method"]), []).append(r)
    presets = ", ".join(dict.fromkeys(r["preset"] for r in rows))
    print("| scene | method | GPU ms %s | GPU MiB | FLIP | RMSE | AO RMSE |" % presets)
    print("|---|---|---|---|---|---|---|")
    for (scene, method), g in groups.items():
        join = lambda key, fmt: ", ".join(fmt(r[key]) for r in g)
        ao = join("ao_rmse", lambda v: "%.3f" % float(v)) if all(r["ao_rmse"] for r in g) else ""
        print("| %s | %s | %s | %s | %s | %s | %s |" % (
            scene, method, join("gpu_ms", ms), join("gpu_bytes", lambda v: "%.1f" % (float(v) / 2**20)),
            join("flip", lambda v: "%.3f" % float(v)), join("rmse", lambda v: "%.4f" % float(v)), ao))


if __name__ == "__main__":
    main()
