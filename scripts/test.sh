#!/usr/bin/env bash
# Install what is missing, build, and run the whole test suite (ctest). CI runs exactly this.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
cd build
ctest --output-on-failure -j"$(nproc)" "$@"
