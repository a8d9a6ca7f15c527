// What C++ and GLSL share, each from the one C++ declaration of it, emitted as #defines before
// every shader's source (gl/shader.h, preprocessShader): the limits and sizes below and every
// module's uniform-location table (gl/uniform_table.h) and uniform block (gl/uniform_block.h).
// GLSL writes none of these numbers itself, so `gisandbox shaders --dump` and the glslangValidator
// test compile every program against them.
#include <string>

#include "emitters/emitter_uniforms.h"
#include "environment_gpu.h"
#include "probes/probe_uniforms.h"
#include "gi/hddagi/hddagi_uniforms.h"
#include "gi/sdf/sdf_gi_uniforms.h"
#include "gl/gl.h"
#include "gl/shader.h"
#include "lights.h"
#include "nonfinite_counter.h"
#include "volume/sdf_uniforms.h"
#include "uniforms.h"
#include "volume/occupancy.h"
#include "volume/volume_cascades.h"
#include "volume/volume_slots.h"
#include "volume/voxel_uniforms.h"

namespace gis {

namespace {
std::string glslFloat(float v) {
    std::string s = std::to_string(v);
    return s.find('.') == std::string::npos ? s + ".0" : s;
}

template <size_t N>
void addTable(std::vector<gl::UniformSlot>& all, const gl::UniformSlot (&table)[N]) {
    all.insert(all.end(), table, table + N);
}
}  // namespace

const std::vector<gl::UniformSlot>& uniformSlots() {
    static const std::vector<gl::UniformSlot> all = [] {
        std::vector<gl::UniformSlot> v;
        addTable(v, kUniforms);
        addTable(v, voxel::kVoxelUniforms);
        addTable(v, emitters::kEmitterUniforms);
        addTable(v, sdf::kSdfUniforms);
        addTable(v, sdfgi::kSdfGiUniforms);
        addTable(v, probes::kProbeUniforms);
        addTable(v, hddagi::kHddagiUniforms);
        return v;
    }();
    return all;
}

const std::vector<gl::UniformBlockDesc>& uniformBlocks() {
    static const std::vector<gl::UniformBlockDesc> all = {
        emitters::RestirBlock::desc(),
        voxel::ConeTraceBlock::desc(),
        voxel::VctDebugBlock::desc(),
        sdf::SdfMarchBlock::desc(),
        sdfgi::SdfDebugBlock::desc(),
        sdfgi::SdfTraceBlock::desc(),
        sdfgi::SdfTemporalBlock::desc(),
        probes::ProbeUpdateBlock::desc(),
        probes::ProbeGatherBlock::desc(),
        hddagi::HddagiSliceBlock::desc(),
        SsaoBlock::desc(),
        SsaoTemporalBlock::desc(),
        EnvironmentBlock::desc(),
    };
    return all;
}

const std::vector<std::pair<std::string, std::string>>& sharedShaderDefines() {
    static const std::vector<std::pair<std::string, std::string>> defines = [] {
        std::vector<std::pair<std::string, std::string>> d{
            {"MAX_HALF_FLOAT", glslFloat(gl::kMaxHalfFloat)},
            {"SDF_MAX_CASCADES", std::to_string(kMaxCascades)},
            {"MAX_AO_KERNEL", std::to_string(kSsaoMaxKernel)},
            {"LIGHTS_BINDING", std::to_string(kLightsBinding)},
            {"OCC_BLOCK", std::to_string(kOccupancyBlock)},
            {"OCC_REGION", std::to_string(kOccupancyRegion)},
            {"OCC_BLOCKS_BINDING", std::to_string(kOccupancyBlocksBinding)},
            {"OCC_REGIONS_BINDING", std::to_string(kOccupancyRegionsBinding)},
            {"VOLUME_DISTANCE_UNIT", std::to_string(kVolumeDistanceUnit)},
            {"VOLUME_COARSE_UNIT", std::to_string(kVolumeCoarseUnit)},
            {"VOLUME_RADIANCE_UNIT", std::to_string(kVolumeRadianceUnit)},
            {"VOLUME_ALBEDO_UNIT", std::to_string(kVolumeAlbedoUnit)},
            {"VOLUME_EMISSION_UNIT", std::to_string(kVolumeEmissionUnit)},
            {"ENV_BRDF_UNIT", std::to_string(kEnvironmentBrdfUnit)},
            {"ENV_RADIANCE_UNIT", std::to_string(kEnvironmentRadianceUnit)},
            {"ENV_SPECULAR_UNIT", std::to_string(kEnvironmentSpecularUnit)},
            {"ENV_MARGINAL_UNIT", std::to_string(kEnvironmentMarginalUnit)},
            {"ENV_CONDITIONAL_UNIT", std::to_string(kEnvironmentConditionalUnit)},
        };
        if (countingNonFinite()) {
            d.emplace_back("COUNT_NONFINITE", "1");
            d.emplace_back("NONFINITE_BINDING", std::to_string(kNonFiniteBinding));
        }
        for (const gl::UniformSlot& u : uniformSlots()) d.emplace_back(u.name, std::to_string(u.location));
        for (const gl::UniformBlockDesc& b : uniformBlocks()) d.emplace_back(b.name, gl::glslBlockDeclaration(b));
        return d;
    }();
    return defines;
}

}  // namespace gis
