// GLSL programs built from files under shaders/. `#include "file.glsl"` is resolved here (each file
// once per stage) and defines are injected after #version. The expanded source keeps a table from
// each of its lines to the file and line it came from, so a compile error is reported as
// "shaders/file.glsl:LINE: message". (A table rather than `#line N FILE` directives: Mesa ignores
// the source-string number of #line in its messages.)
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "gl/gl.h"
#include "gl/storage_struct.h"
#include "gl/uniform_block.h"
#include "gl/uniform_table.h"

namespace gis {

// A program the app can request: its stage files and the defines of one permutation.
struct ProgramDesc {
    std::string name;                   // for messages and the shader dump
    std::vector<std::string> stages;    // file names in shaders/: *.vert *.geom *.frag *.comp
    std::vector<std::pair<std::string, std::string>> defines;  // NAME, value
};

struct PreprocessedShader {
    struct Origin {
        std::string file;               // "shaders/NAME"
        int line = 0;                   // 1-based line in that file; 0 for injected lines
    };
    std::string source;                 // ready for glShaderSource / glslangValidator
    std::vector<Origin> lines;          // origin of each line of `source`
};

std::string shaderDir();  // GIS_SHADER_DIR environment variable, else the build's source path
// The source of one stage: the version line, sharedShaderDefines(), the program's `defines`, then
// the file with its #includes expanded.
PreprocessedShader preprocessShader(const std::string& file,
                                    const std::vector<std::pair<std::string, std::string>>& defines);
// Every limit and size C++ and GLSL share, as #define NAME VALUE from the one C++ constant that
// declares it (renderer/shader_constants.cpp), so the two cannot drift apart.
const std::vector<std::pair<std::string, std::string>>& sharedShaderDefines();
// Every module's uniform-location rows together (what sharedShaderDefines emits of them).
const std::vector<gl::UniformSlot>& uniformSlots();
// Every module's uniform blocks (what sharedShaderDefines emits of them, each as its declaration).
const std::vector<gl::UniformBlockDesc>& uniformBlocks();
// What a module shares with GLSL beyond the frame's own tables (renderer/shader_constants.cpp):
// its uniform rows, binding points and uniform blocks. A GI method brings its own in its registry
// entry, so adding one touches only its folders and the registry's line.
struct ShaderTables {
    std::vector<gl::UniformSlot> uniforms;
    std::vector<gl::BindingSlot> bindings;
    std::vector<gl::UniformBlockDesc> blocks;
};
template <class Slot, size_t N>
std::vector<Slot> tableRows(const Slot (&table)[N]) {
    return {table, table + N};
}
// Every registered GI method's tables, in registry order (defined by the registry,
// renderer/gi/method.cpp). Emitted once, when the first shader is built: a method registered later
// (a test's) brings none.
std::vector<ShaderTables> methodShaderTables();
// Every module's binding points (texture and image units, buffer bindings; emitted as #defines).
const std::vector<gl::BindingSlot>& bindingSlots();
// Every storage-buffer struct (gl/storage_struct.h; emitted as STRUCT_NAME, its declaration).
const std::vector<gl::StorageStructDesc>& storageStructs();
// Rewrites "0:LINE(COL): msg" (Mesa) and "0(LINE) : msg" (NVIDIA) into "shaders/file:LINE: msg".
std::string mapShaderLog(const std::string& log, const PreprocessedShader& shader);

// Compiles and links; throws gis::Error naming the file and line of the first error.
gl::Object buildProgram(const ProgramDesc& desc);

}  // namespace gis
