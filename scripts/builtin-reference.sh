#!/usr/bin/env bash
# Renders a Blender Cycles reference of a built-in scene with ../shared/tools/cycles-ref.py:
# exports builtin:SCENE with `gisandbox export`, tags every material that is an ideal Lambertian
# here (specularFactor 0, metallic 0) so Cycles renders it as one, leaves the others to Blender's
# glTF importer (Principled BSDF: the metals of builtin:mirror), lights it with the sky radiance
# export names (if any), and copies full/direct/indirect.exr, full.png and meta.json to OUT.
#
# Environment: ENV_HDR=FILE lights it by that map instead (cycles-ref.py --env-hdr, Blender's
# mapping, which is ours) and NO_LIGHTS=1 drops the file's punctual lights (a scene lit by its map
# alone: render ours with --environment FILE --lighting none).
#
# Usage (project root, after a build; needs `apt-get install blender python3-numpy`):
#   bash scripts/builtin-reference.sh SCENE OUT [SPP (2048)] [cycles-ref.py camera args ...]
#   e.g. bash scripts/builtin-reference.sh mirror assets/reference/mirror 1024
set -euo pipefail
cd "$(dirname "$0")/.."
case "${1:-}" in -h|--help|"") sed -n '2,15p' "$0"; exit 0 ;; esac
scene=$1 out=$2 spp=${3:-2048}
shift $(( $# >= 3 ? 3 : $# ))
bin=${BIN:-build/gisandbox}
tool=../shared/tools/cycles-ref.py
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# The sky is not in the file; export names it ("... a sky of radiance (R, G, B) ...").
"$bin" export --scene "builtin:$scene" --out "$work/scene.gltf" > "$work/export.log" 2>&1 ||
  { cat "$work/export.log" >&2; exit 1; }
sky=$(sed -n 's/.*sky of radiance (\([^)]*\)).*/\1/p' "$work/export.log" | tr -d ',')
/usr/bin/python3 - "$work/scene.gltf" "${NO_LIGHTS:-0}" <<'PY'
import json, sys
path = sys.argv[1]
g = json.load(open(path))
if sys.argv[2] == "1":
    g.get("extensions", {}).pop("KHR_lights_punctual", None)
    g["extensionsUsed"] = [e for e in g.get("extensionsUsed", []) if e != "KHR_lights_punctual"]
    for n in g.get("nodes", []):
        n.get("extensions", {}).pop("KHR_lights_punctual", None)
for m in g["materials"]:
    pbr = m.get("pbrMetallicRoughness", {})
    spec = m.get("extensions", {}).get("KHR_materials_specular", {}).get("specularFactor", 1.0)
    if spec == 0.0 and pbr.get("metallicFactor", 1.0) == 0.0:
        m.setdefault("extras", {})["ref_bsdf"] = "lambert"
    else:
        print("principled (Blender's glTF importer):", m.get("name"), file=sys.stderr)
json.dump(g, open(path, "w"))
PY
world=()
if [ -n "${ENV_HDR:-}" ]; then world=(--env-hdr "$(realpath "$ENV_HDR")")
elif [ -n "$sky" ]; then world=(--world $sky); fi
blender -b --factory-startup --python "$tool" -- --gltf "$work/scene.gltf" --out "$work/render" \
  --passes full,direct --res 256 256 --spp "$spp" "${world[@]}" "$@" > "$work/render.log" 2>&1 ||
  { tail -20 "$work/render.log" >&2; exit 1; }
mkdir -p "$out"
cp "$work/render"/{full,direct,indirect}.exr "$work/render"/full.png "$work/render"/meta.json "$out/"
echo "wrote $out ($(grep -o '"total_seconds[^,}]*' "$work/render/meta.json"))" >&2
