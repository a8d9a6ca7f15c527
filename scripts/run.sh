#!/usr/bin/env bash
# The main job: install what is missing, build, and render the default comparison scene headless.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
mkdir -p screenshots
./build/gisandbox render --scene builtin:cornell --size 512x512 --out screenshots/cornell.png -v "$@"
