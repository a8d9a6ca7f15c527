// GLSL programs built from files under shaders/. `#include "file.glsl"` is resolved here (each file
// once per stage), defines are injected after #version, and `#line` directives keep a source-string
// number per file so a compile error can be reported as "shaders/file.glsl:LINE: message".
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "gl/gl.h"

namespace gis {

// A program the app can request: its stage files and the defines of one permutation.
struct ProgramDesc {
    std::string name;                   // for messages and the shader dump
    std::vector<std::string> stages;    // file names in shaders/: *.vert *.geom *.frag *.comp
    std::vector<std::pair<std::string, std::string>> defines;  // NAME, value
};

struct PreprocessedShader {
    std::string source;                 // ready for glShaderSource / glslangValidator
    std::vector<std::string> files;     // source-string number -> file path (for error mapping)
};

std::string shaderDir();  // GIS_SHADER_DIR environment variable, else the build's source path
PreprocessedShader preprocessShader(const std::string& file,
                                    const std::vector<std::pair<std::string, std::string>>& defines);
// Rewrites "N:LINE(COL): msg" (Mesa) and "N(LINE) : msg" (NVIDIA) into "file:LINE: msg".
std::string mapShaderLog(const std::string& log, const std::vector<std::string>& files);

// Compiles and links; throws gis::Error naming the file and line of the first error.
gl::Object buildProgram(const ProgramDesc& desc);

}  // namespace gis
