#!/usr/bin/env bash
# Renders the Blender Cycles reference of builtin:building (assets/reference/building/) with
# scripts/builtin-reference.sh (every material of the building is an ideal Lambertian): the
# corridor (camera 0) and the hall (camera 1) with the scene's sky. The closed room needs no
# reference: no light reaches it, so its truth is black.
#
# Usage (project root, after a build; needs `apt-get install blender python3-numpy`):
#   bash scripts/building-reference.sh [BIN (build/gisandbox)] [SPP (2048)]
set -euo pipefail
cd "$(dirname "$0")/.."
case "${1:-}" in -h|--help) sed -n '2,8p' "$0"; exit 0 ;; esac
export BIN=${1:-build/gisandbox}
spp=${2:-2048}
out=assets/reference/building
bash scripts/builtin-reference.sh building "$out/corridor" "$spp"
# Camera 1 as the scene declares it (renderer/scene/builtin_gi_scenes.cpp): the tool reads only the first.
bash scripts/builtin-reference.sh building "$out/hall" "$spp" --cam-pos -15 1.7 -4.8 --cam-target 2 0.9 1.0 --yfov-deg 60
