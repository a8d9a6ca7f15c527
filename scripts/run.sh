#!/usr/bin/env bash
# The main job: install what is missing, build, then
#  - with a display (DISPLAY set) and no arguments: open the interactive sandbox on builtin:cornell;
#  - otherwise, or when the window cannot open (no GL 4.5 on that display): render the default
#    comparison scene headless to screenshots/cornell.png. Arguments go to `gisandbox render`.
# GIS_HEADLESS=1 forces the headless render.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
mkdir -p screenshots
if [ $# -eq 0 ] && [ -n "${DISPLAY:-}" ] && [ "${GIS_HEADLESS:-0}" != 1 ]; then
  echo "run: display $DISPLAY found, opening the interactive sandbox (GIS_HEADLESS=1 renders headless instead)" >&2
  if ./build/gisandbox view --scene builtin:cornell -v; then
    exit 0
  fi
  echo "run: the window could not be used; rendering headless instead" >&2
fi
./build/gisandbox render --scene builtin:cornell --size 512x512 --out screenshots/cornell.png -v "$@"
