// Storage-buffer structs and binding points are declared once in C++ (gl/storage_struct.h,
// gl/uniform_table.h) and emitted into every shader: compiled from that declaration, GL lays each
// struct out as std430 exactly as its C++ struct.
#include <gtest/gtest.h>

#include <map>
#include <set>
#include <string>

#include "gl/shader.h"
#include "render_test_util.h"

namespace gis::test {
namespace {

// A compute program holding `s` in an unsized storage array and touching its first member.
gl::Object compileStructProbe(const gl::StorageStructDesc& s, std::string& log) {
    std::string source = "#version 450 core\n";
    for (const auto& [name, value] : sharedShaderDefines()) source += "#define " + name + " " + value + "\n";
    const gl::UniformBlockDesc::Member& first = s.members.front();
    const std::string type = first.type;
    const std::string touch = std::string("u_items[0].") + first.name +
                              (type == "mat4" ? "[0][0]" : type.find("vec") != std::string::npos ? ".x" : "");
    source += std::string("STRUCT_") + s.name + "\nlayout(local_size_x = 1) in;\n" +
              "layout(std430, binding = 0) buffer Items { " + s.name + " u_items[]; };\n" +
              "layout(std430, binding = 1) buffer Out { float o[]; };\n" + "void main() { o[0] = float(" + touch + "); }\n";
    const char* text = source.c_str();
    gl::Object program(glCreateShaderProgramv(GL_COMPUTE_SHADER, 1, &text), [](GLuint id) { glDeleteProgram(id); });
    char buffer[2048] = {};
    glGetProgramInfoLog(program.id(), sizeof(buffer), nullptr, buffer);
    log = std::string(buffer) + "\n" + source;
    return program;
}

GLint resourceValue(GLuint program, GLenum interface, const std::string& name, GLenum property) {
    const GLuint index = glGetProgramResourceIndex(program, interface, name.c_str());
    if (index == GL_INVALID_INDEX) return -1;
    GLint value = -1;
    glGetProgramResourceiv(program, interface, index, 1, &property, 1, nullptr, &value);
    return value;
}

TEST(Shaders, StorageStructsAreLaidOutAsTheirCppStructs) {
    context();
    ASSERT_FALSE(storageStructs().empty());
    std::set<std::string> names;
    for (const gl::StorageStructDesc& s : storageStructs()) {
        EXPECT_TRUE(names.insert(s.name).second) << s.name << " is declared twice";
        std::string log;
        gl::Object program = compileStructProbe(s, log);
        GLint linked = 0;
        glGetProgramiv(program.id(), GL_LINK_STATUS, &linked);
        ASSERT_TRUE(linked) << s.name << ": " << log;
        for (const gl::UniformBlockDesc::Member& m : s.members) {
            const std::string member = std::string("u_items[0].") + m.name;
            const GLint offset = resourceValue(program.id(), GL_BUFFER_VARIABLE, member, GL_OFFSET);
            ASSERT_GE(offset, 0) << member << " is not in the program";
            EXPECT_EQ(size_t(offset), m.offset) << s.name << "." << m.name << ": GLSL and C++ disagree on its offset";
        }
        const std::string first = std::string("u_items[0].") + s.members.front().name;
        const GLint stride = resourceValue(program.id(), GL_BUFFER_VARIABLE, first, GL_TOP_LEVEL_ARRAY_STRIDE);
        EXPECT_EQ(size_t(stride), s.size) << s.name << ": std430's array stride is not sizeof the C++ struct";
    }
}

// Binding points are emitted as #defines beside the uniform locations: a name taken twice would
// make one table's point the other's in every shader.
TEST(Shaders, BindingPointsHaveOneNameEachAndReachTheShaders) {
    std::map<std::string, std::string> defines(sharedShaderDefines().begin(), sharedShaderDefines().end());
    std::set<std::string> names;
    for (const gl::UniformSlot& u : uniformSlots()) names.insert(u.name);
    ASSERT_FALSE(bindingSlots().empty());
    for (const gl::BindingSlot& b : bindingSlots()) {
        EXPECT_TRUE(names.insert(b.name).second) << b.name << " is declared twice";
        EXPECT_GE(b.point, 0) << b.name;
        EXPECT_EQ(defines[b.name], std::to_string(b.point)) << b.name;
    }
}

}  // namespace
}  // namespace gis::test
