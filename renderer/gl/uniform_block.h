// Uniform blocks declared once: a module lists a block's members in GLSL types, and that one list
// becomes both the C++ struct the pass fills (aligned as std140 lays the block out) and the GLSL
// declaration emitted into every shader's preamble (renderer/shader_constants.cpp) as
//   #define NAME layout(std140, binding = B) uniform NAME { MEMBERS }
// which a shader instantiates with `NAME u_name;` (the name inside its own expansion is not expanded
// again). Named members replace vec4 uniforms that
// packed unrelated values by position, and C++ and GLSL cannot disagree on order, type or binding;
// the shader-constants test compiles every block and compares GL's member offsets with offsetof.
//
// Member types: float, int, uint, vec4, ivec4, mat4, and arrays of vec4, ivec4 or mat4 (whose std140
// stride is their size; scalar arrays and vec3 are left out, since std140 pads them unlike C++).
// A module writes its list as MEMBERS(M, A) with M(TYPE, NAME) and A(TYPE, NAME, COUNT) rows.
#pragma once

#include <glad/gl.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "gl/gl.h"

namespace gis::gl {

// One block as the shader preamble and the layout test see it.
struct UniformBlockDesc {
    struct Member {
        const char* type;  // GLSL type
        const char* name;
        int count;         // 0: not an array
        size_t offset;     // offsetof in the C++ struct
    };
    const char* name;      // the GLSL block name, also the C++ struct's
    int binding;           // GL_UNIFORM_BUFFER binding point
    size_t size;           // sizeof the C++ struct
    std::vector<Member> members;
};

// "layout(std140, binding = B) uniform NAME { TYPE MEMBER; ... }", the instance name left to the shader.
std::string glslBlockDeclaration(const UniformBlockDesc& block);

// A block's buffer, charged to its pass: set() uploads the values and binds the buffer to the
// block's binding point, so call it right before the draws or dispatches that read them.
template <class Block>
class UniformBuffer {
public:
    explicit UniformBuffer(const MemoryScope& scope)
        : buffer_(createBuffer(scope, int64_t(sizeof(Block)), nullptr, GL_DYNAMIC_STORAGE_BIT)) {}
    void set(const Block& values) const {
        glNamedBufferSubData(buffer_.id(), 0, GLsizeiptr(sizeof(Block)), &values);
        glBindBufferBase(GL_UNIFORM_BUFFER, GLuint(Block::kBinding), buffer_.id());
    }

private:
    Buffer buffer_;
};

}  // namespace gis::gl

#define GIS_STD140_CPP_float float
#define GIS_STD140_CPP_int int32_t
#define GIS_STD140_CPP_uint uint32_t
#define GIS_STD140_CPP_vec4 glm::vec4
#define GIS_STD140_CPP_ivec4 glm::ivec4
#define GIS_STD140_CPP_mat4 glm::mat4
#define GIS_STD140_ALIGN_float 4
#define GIS_STD140_ALIGN_int 4
#define GIS_STD140_ALIGN_uint 4
#define GIS_STD140_ALIGN_vec4 16
#define GIS_STD140_ALIGN_ivec4 16
#define GIS_STD140_ALIGN_mat4 16

#define GIS_STD140_MEMBER(type, name) alignas(GIS_STD140_ALIGN_##type) GIS_STD140_CPP_##type name{};
#define GIS_STD140_ARRAY(type, name, count)                                                 \
    static_assert(GIS_STD140_ALIGN_##type == 16, #name ": std140 arrays of scalars are padded"); \
    alignas(16) GIS_STD140_CPP_##type name[count]{};
#define GIS_STD140_MEMBER_DESC(type, name) {#type, #name, 0, offsetof(Self, name)},
#define GIS_STD140_ARRAY_DESC(type, name, count) {#type, #name, int(count), offsetof(Self, name)},

// struct NAME with the members of MEMBERS(M, A), its binding point and its description.
#define GIS_UNIFORM_BLOCK(NAME, BINDING, MEMBERS)                                             \
    struct alignas(16) NAME {                                                                 \
        MEMBERS(GIS_STD140_MEMBER, GIS_STD140_ARRAY)                                          \
        static constexpr int kBinding = BINDING;                                              \
        static_assert(BINDING >= 1, #NAME ": binding 0 is the lights' block");               \
        static ::gis::gl::UniformBlockDesc desc() {                                           \
            using Self = NAME;                                                                \
            return {#NAME, BINDING, sizeof(Self), {MEMBERS(GIS_STD140_MEMBER_DESC, GIS_STD140_ARRAY_DESC)}}; \
        }                                                                                     \
    };                                                                                        \
    static_assert(sizeof(NAME) <= 16384, #NAME ": past GL 4.5's minimum GL_MAX_UNIFORM_BLOCK_SIZE");
