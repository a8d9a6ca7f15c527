#!/usr/bin/env bash
# The measured tables of renderer/emitters/README.md: runs the emitter tests that print them (a
# gtest filter, default every table and the furnace) and prints each NAME-TABLE line as a Markdown
# row under its NAME, in the order printed. The README's rows are this output, pasted.
#   bash scripts/emitter-tables.sh ['EmitterFurnace.*:*PanelRoom*'] [build/tests/gis_emitter_tests]
set -euo pipefail
cd "$(dirname "$0")/.."
filter=${1:-'*Table*:EmitterFurnace.*'}
bin=${2:-build/tests/gis_emitter_tests}
"$bin" --gtest_also_run_disabled_tests --gtest_filter="$filter" | awk '
  match($0, /^[A-Z-]+-TABLE /) {
    name = substr($0, 1, RLENGTH - 1)
    if (name != last) { printf "\n%s\n", name; last = name }
    print substr($0, RLENGTH + 1)
  }'
