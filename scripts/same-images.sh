#!/usr/bin/env bash
# Renders every registered method on every built-in scene a refactoring must not change, at 64x64, and prints one
# SHA-256 per linear EXR: run it with the binaries of two commits and diff the two lists (a
# refactoring that keeps behaviour gives the same list).
#   bash scripts/same-images.sh BUILD/gisandbox OUT_DIR > list.txt
set -euo pipefail
bin=${1:?usage: same-images.sh GISANDBOX OUT_DIR}
out=${2:?usage: same-images.sh GISANDBOX OUT_DIR}
mkdir -p "$out"
methods=${SAME_IMAGES_METHODS:-$("$bin" methods | awk '$1 != "emitters" && /^[a-z]/ {print $1}')}
scenes=${SAME_IMAGES_SCENES:-builtin:cornell builtin:cornell-area builtin:brdf-gallery builtin:leak builtin:room builtin:mirror builtin:atrium}
for scene in $scenes; do
  for m in $methods; do
    f="$out/${scene#builtin:}-$m.exr"
    "$bin" render --scene "$scene" --gi "$m" --size 64x64 --out "$f" >/dev/null 2>"$f.log" ||
      { echo "render failed: $scene $m (see $f.log)" >&2; exit 1; }
    printf '%s  %s\n' "$(sha256sum < "$f" | cut -d' ' -f1)" "${scene#builtin:}-$m"
  done
done
