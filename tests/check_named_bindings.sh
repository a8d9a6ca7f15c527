#!/usr/bin/env sh
# Binding points are declared once, in C++ tables (gl/uniform_table.h), and emitted into GLSL: no
# shader writes `binding = N` and no C++ bind call names its unit or binding by number.
src=$1
status=0
if grep -rnE 'binding *= *[0-9]' "$src/shaders"; then
  echo "literal binding points in GLSL (above): declare them in a binding table"; status=1
fi
if grep -rnE 'glBind(Textures|Samplers|ImageTextures?|TextureUnit|BufferBase|BufferRange|Sampler)\( *(GL_[A-Z_]+, *)?[0-9]' \
     "$src/renderer" "$src/app" "$src/tests"; then
  echo "literal units in C++ bind calls (above): bind at the table's names"; status=1
fi
exit $status
