#!/usr/bin/env bash
# Renders the Blender Cycles reference of builtin:building (assets/reference/building/): exports
# the built-in scene with `gisandbox export`, tags its materials as ideal Lambertians (every one is:
# specularFactor 0, metallic 0) for ../shared/tools/cycles-ref.py, and renders the corridor
# (camera 0) and the hall (camera 1) with the scene's sky. The closed room needs no reference: no
# light reaches it, so its truth is black.
#
# Usage (project root, after a build; needs `apt-get install blender python3-numpy`):
#   bash scripts/building-reference.sh [BIN (build/gisandbox)] [SPP (2048)]
set -euo pipefail
cd "$(dirname "$0")/.."
bin=${1:-build/gisandbox}
spp=${2:-2048}
out=assets/reference/building
tool=../shared/tools/cycles-ref.py
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# The sky is not in the file; export names it ("... a sky of radiance (R, G, B) ...").
sky=$("$bin" export --scene builtin:building --out "$work/building.gltf" 2>&1 |
      sed -n 's/.*sky of radiance (\([^)]*\)).*/\1/p' | tr -d ',')
[ -n "$sky" ] || { echo "export named no sky radiance" >&2; exit 1; }
python3 - "$work/building.gltf" <<'PY'
import json, sys
path = sys.argv[1]
g = json.load(open(path))
for m in g["materials"]:
    pbr = m.get("pbrMetallicRoughness", {})
    spec = m.get("extensions", {}).get("KHR_materials_specular", {}).get("specularFactor", 1.0)
    assert spec == 0.0 and pbr.get("metallicFactor", 1.0) == 0.0, m["name"] + " is not a Lambertian"
    m.setdefault("extras", {})["ref_bsdf"] = "lambert"
json.dump(g, open(path, "w"))
PY
render() {  # NAME [camera args]
  local name=$1; shift
  blender -b --factory-startup --python "$tool" -- --gltf "$work/building.gltf" --out "$work/$name" \
    --passes full,direct --res 256 256 --spp "$spp" --world $sky "$@" > "$work/$name.log" 2>&1 ||
    { tail -20 "$work/$name.log" >&2; exit 1; }
  mkdir -p "$out/$name"
  cp "$work/$name"/{full,direct,indirect}.exr "$work/$name"/full.png "$work/$name"/meta.json "$out/$name/"
  echo "wrote $out/$name ($(grep -o '"total_seconds[^,}]*' "$work/$name/meta.json"))" >&2
}
render corridor
# Camera 1 as the scene declares it (renderer/scene/builtin_gi_scenes.cpp): the tool reads only the first.
render hall --cam-pos -15 1.7 -4.8 --cam-target 2 0.9 1.0 --yfov-deg 60
