#!/usr/bin/env bash
# Dumps every program/permutation the app can request (gisandbox shaders --dump) and compiles each
# stage with glslangValidator, which needs no GPU. Fails on the first error, printing it.
set -euo pipefail
gisandbox=$1 validator=$2 dir=$3
rm -rf "$dir"
"$gisandbox" shaders --dump "$dir"
count=0
for f in "$dir"/*; do
  stage=${f##*.}
  if ! "$validator" -S "$stage" "$f" >"$f.log" 2>&1; then
    echo "glslangValidator failed on $(basename "$f"):"; cat "$f.log"; exit 1
  fi
  count=$((count + 1))
done
[ "$count" -gt 0 ] || { echo "no shader stages were dumped"; exit 1; }
echo "$count shader stages compiled"
