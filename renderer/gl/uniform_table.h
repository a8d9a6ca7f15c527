// Explicit uniform locations, declared once in C++ as a table per module and emitted as
// `#define NAME LOCATION` before every shader's source (renderer/shader_constants.cpp): fixed
// locations mean no glGetUniformLocation lookups, and one table means GLSL cannot drift from C++.
// A module's header lists its rows as X(NAME, LOCATION, COUNT) (COUNT: locations an array takes)
// and derives its enum and its table from them with the two macros below.
#pragma once

namespace gis::gl {

struct UniformSlot {
    const char* name;
    int location;
    int count;  // consecutive locations (an array uniform takes one per element)
};

}  // namespace gis::gl

#define GIS_UNIFORM_ENUM(name, location, count) name = location,
#define GIS_UNIFORM_SLOT(name, location, count) {#name, location, count},
