# The helpers the method-page table scripts share (sourced, not run): they need $bin (the
# gisandbox binary) and $tmp (a scratch folder) set first.

render() {  # OUT flags...: renders or exits naming what failed
  local out=$1; shift
  timeout 1800 "$bin" render --out "$out" "$@" > "$tmp/log" 2>&1 ||
    { echo "$(basename "$0" .sh): render $* failed:" >&2; tail -3 "$tmp/log" >&2; exit 1; }
}
compare() {  # TEST REF [diff flags] -> "PSNR / mean ratio"
  "$bin" diff "$@" | awk '/^PSNR sRGB/ {p = $3} /^mean ratio/ {m = $3} END {printf "%.1f dB / %.2f", p, m}'
}
passMs() {  # PASS FRAMES render-flags... -> PASS's GPU ms per frame (--timings: every pass every frame), or nothing
  local pass=$1 frames=$2; shift 2
  timeout 1800 "$bin" render --out "$tmp/timings.png" "$@" --timings --frames "$frames" 2>&1 |
    awk -v p="$pass" '$1 == p && !ms {ms = $2} END {print ms}'
}
ratio() {  # TEST REF [diff flags] -> the mean ratio alone
  "$bin" diff "$@" | awk '/^mean ratio/ {printf "%.3f", $3}'
}

# The real-scale columns against Cycles at 256x256 (issue #39): cyclesRenders FLAGS... renders the
# atrium courtyard, builtin:building's corridor, hall and closed room, and cornell_point with the
# method's flags (in this shell, so that a failed render ends the script); cyclesColumns then prints
# their columns, each led by " | ": atrium, corridor and hall ("PSNR / mean ratio"), the building's
# leak number (its closed room's mean over the corridor's) and cornell_point (PSNR alone). Both
# need the project root as the working folder.
cyclesRenders() {
  local shared=../shared/assets
  render "$tmp/atrium.exr" --scene "$shared/reference/scenes/atrium/atrium.gltf" --background 0.35,0.45,0.6 "$@" --size 256x256
  render "$tmp/corridor.exr" --scene builtin:building --camera 0 "$@" --size 256x256
  render "$tmp/hall.exr" --scene builtin:building --camera 1 "$@" --size 256x256
  render "$tmp/closed.exr" --scene builtin:building --camera 2 "$@" --size 256x256
  render "$tmp/cornell.exr" --scene "$shared/reference/scenes/cornell_point/cornell_point.gltf" "$@" --size 256x256
}
cyclesColumns() {
  local shared=../shared/assets
  echo -n " | $(compare "$tmp/atrium.exr" "$shared/reference/refs/atrium/full.exr")"
  echo -n " | $(compare "$tmp/corridor.exr" assets/reference/building/corridor/full.exr)"
  echo -n " | $(compare "$tmp/hall.exr" assets/reference/building/hall/full.exr)"
  echo -n " | $(ratio "$tmp/closed.exr" "$tmp/corridor.exr")"
  echo -n " | $(compare "$tmp/cornell.exr" "$shared/reference/refs/cornell_point/full.exr" | sed 's| / .*||')"
}

sdfCosts() {  # flags... -> "probes | probe ms | gather ms": SDF GI's probes in builtin:building (every cascade)
  # and the corridor's GPU ms at 256x256 for them (trace and blends) and for the gather (trace and
  # filter), every pass executed each frame
  timeout 1800 "$bin" render --scene builtin:building --camera 0 --size 256x256 --timings --rerun-settled --frames 4 \
    --warmup 1 --out "$tmp/timed.png" "$@" 2>/dev/null |
    awk '/SDFGI probes/ {n = $NF; for (i = 1; i <= NF; ++i) if ($i == "=") n = $(i + 1); sub(",", "", n)}
         $1 == "probe" && ($2 == "trace" || $2 == "blend") {p += ($2 == "trace") ? $3 : $4}
         $1 == "trace" {g += $2} $1 == "filter" {g += $2}
         END {printf "%s | %.0f | %.0f", n, p, g}'
}
