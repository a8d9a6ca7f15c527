#!/bin/sh
# Builds the libFuzzer target of the viewer's text inputs (fuzz_view_inputs.cpp) with clang++:
# the target and the parsers it drives (app/cli/settings_io.cpp, app/view/view_script.cpp,
# app/cli/panel_action.cpp, app/cli/view_state.cpp) are compiled here with ASan + UBSan and coverage; the rest of the program
# (method registry, renderer) is linked from an existing GCC build's static libraries,
# uninstrumented. Usage: tests/view/fuzz/build_fuzzer.sh BUILD_DIR OUT_BINARY (e.g. build build/fuzz-view/fuzz_view_inputs)
# Run:   OUT_BINARY -dict=tests/view/fuzz/view.dict CORPUS_DIR tests/view/fuzz/seeds
set -eu
build=$1
out=$2
root=$(cd "$(dirname "$0")/../../.." && pwd)
cxx=${CLANGXX:-clang++}
san="-fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer"
inc="-I$root/app -I$root/renderer -I$build/glad/include -isystem /usr/include/stb"
objs=""
for src in tests/view/fuzz/fuzz_view_inputs.cpp app/cli/settings_io.cpp app/view/view_script.cpp app/cli/panel_action.cpp app/cli/view_state.cpp; do
  obj="$out.$(basename "$src" .cpp).o"
  $cxx -std=c++17 -O1 -g $san -fsanitize=fuzzer-no-link $inc -c "$root/$src" -o "$obj"
  objs="$objs $obj"
done
# The libraries' other members only; the instrumented objects above come first and win.
$cxx $san -fsanitize=fuzzer -o "$out" $objs \
  "$build/libgis_app.a" "$build/libgis_renderer.a" "$build/libgis_image.a" "$build/libgis_scene.a" "$build/libgis_glad.a" \
  -ltinygltf -lembree3 -ltinyexr -lglfw -lEGL -lOSMesa -lcrypto -lstb -ldl -lpthread
