// Storage-buffer structs declared once (std430): a module lists a struct's members in GLSL types,
// and that one list becomes both the C++ struct it uploads and the GLSL declaration emitted into
// every shader's preamble (renderer/shader_constants.cpp) as
//   #define STRUCT_NAME struct NAME { MEMBERS };
// which a shader declares the type with by writing `STRUCT_NAME` on a line of its own. The
// shader-constants test puts each struct in a storage buffer and compares GL's member offsets and
// array stride with offsetof and sizeof, so C++ and GLSL cannot disagree on order, type or padding.
//
// Member types: float, int, uint, vec3, vec4, ivec4, mat4. std430 aligns a vec3 to 16 bytes and
// lets a scalar after it fill its last 4, as C++ does with an alignas(16) glm::vec3; a struct's
// alignment is its largest member's in both.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "gl/uniform_block.h"

namespace gis::gl {

struct StorageStructDesc {
    const char* name;  // the GLSL struct's name, also the C++ struct's
    size_t size;       // sizeof the C++ struct: the array stride std430 must give it
    std::vector<UniformBlockDesc::Member> members;
};

// "struct NAME { TYPE MEMBER; ... };"
std::string glslStructDeclaration(const StorageStructDesc& s);

}  // namespace gis::gl

#define GIS_STD430_MEMBER(type, name) alignas(GIS_STD430_ALIGN_##type) GIS_STD430_TYPE_##type name{};
#define GIS_STD430_TYPE_float float
#define GIS_STD430_TYPE_int int32_t
#define GIS_STD430_TYPE_uint uint32_t
#define GIS_STD430_TYPE_vec3 glm::vec3
#define GIS_STD430_TYPE_vec4 glm::vec4
#define GIS_STD430_TYPE_ivec4 glm::ivec4
#define GIS_STD430_TYPE_mat4 glm::mat4
#define GIS_STD430_ALIGN_vec3 16
#define GIS_STD430_ALIGN_float 4
#define GIS_STD430_ALIGN_int 4
#define GIS_STD430_ALIGN_uint 4
#define GIS_STD430_ALIGN_vec4 16
#define GIS_STD430_ALIGN_ivec4 16
#define GIS_STD430_ALIGN_mat4 16

// struct NAME with the members of MEMBERS(M) (rows M(TYPE, NAME)) and its description.
#define GIS_STORAGE_STRUCT(NAME, MEMBERS)                                                        \
    struct NAME {                                                                                \
        MEMBERS(GIS_STD430_MEMBER)                                                               \
        static ::gis::gl::StorageStructDesc desc() {                                             \
            using Self = NAME;                                                                   \
            return {#NAME, sizeof(Self), {MEMBERS(GIS_STD140_MEMBER_DESC)}};                     \
        }                                                                                        \
    };
