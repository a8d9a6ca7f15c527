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
ratio() {  # TEST REF -> the mean ratio alone
  "$bin" diff "$1" "$2" | awk '/^mean ratio/ {printf "%.3f", $3}'
}
