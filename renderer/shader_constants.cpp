// The limits and sizes C++ and GLSL share, each from the one C++ constant that declares it, emitted
// as #defines before every shader's source (gl/shader.h, preprocessShader): GLSL never writes one
// of these numbers itself, so `gisandbox shaders --dump` and the glslangValidator test compile every
// program against this table.
#include <string>

#include "gi/ssao/ssao_pass.h"
#include "gl/gl.h"
#include "gl/shader.h"
#include "volume/volume_cascades.h"

namespace gis {

namespace {
std::string glslFloat(float v) {
    std::string s = std::to_string(v);
    return s.find('.') == std::string::npos ? s + ".0" : s;
}
}  // namespace

const std::vector<std::pair<std::string, std::string>>& sharedShaderDefines() {
    static const std::vector<std::pair<std::string, std::string>> defines{
        {"MAX_HALF_FLOAT", glslFloat(gl::kMaxHalfFloat)},
        {"SDF_MAX_CASCADES", std::to_string(kMaxCascades)},
        {"MAX_AO_KERNEL", std::to_string(kSsaoMaxKernel)},
    };
    return defines;
}

}  // namespace gis
