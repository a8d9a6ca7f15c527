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

// Binding points (texture and image units, storage-buffer bindings) are declared the same way:
// rows X(NAME, POINT) in a module's table, emitted as `#define NAME POINT`, so GLSL writes
// `layout(binding = NAME)` and C++ binds at NAME and neither writes the number. A point may repeat
// across tables (units of different kinds, programs that never run together); a name may not.
namespace gis::gl {
struct BindingSlot {
    const char* name;
    int point;
};
}  // namespace gis::gl

#define GIS_BINDING_ENUM(name, point) name = point,
#define GIS_BINDING_SLOT(name, point) {#name, point},
