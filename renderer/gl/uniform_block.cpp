#include "gl/uniform_block.h"
#include "gl/storage_struct.h"

namespace gis::gl {

std::string glslBlockDeclaration(const UniformBlockDesc& block) {
    std::string s = "layout(std140, binding = " + std::to_string(block.binding) + ") uniform " + block.name + " {";
    for (const UniformBlockDesc::Member& m : block.members) {
        s += std::string(" ") + m.type + " " + m.name;
        if (m.count > 0) s += "[" + std::to_string(m.count) + "]";
        s += ";";
    }
    return s + " }";
}

std::string glslStructDeclaration(const StorageStructDesc& st) {
    std::string s = std::string("struct ") + st.name + " {";
    for (const UniformBlockDesc::Member& m : st.members) s += std::string(" ") + m.type + " " + m.name + ";";
    return s + " };";
}

}  // namespace gis::gl
