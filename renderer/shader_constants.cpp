// What C++ and GLSL share, each from the one C++ declaration of it, emitted as #defines before
// every shader's source (gl/shader.h, preprocessShader): the limits and sizes below and every frame
// module's uniform-location and binding tables (gl/uniform_table.h), uniform blocks
// (gl/uniform_block.h) and storage-buffer structs (gl/storage_struct.h); each GI method's own
// tables come from its registry entry (GiMethod::shaderTables).
// GLSL writes none of these numbers itself, so `gisandbox shaders --dump` and the glslangValidator
// test compile every program against them.
#include <string>

#include "emitters/emitter_uniforms.h"
#include "environment_gpu.h"
#include "probes/probe_uniforms.h"
#include "gl/gl.h"
#include "gl/shader.h"
#include "lights.h"
#include "nonfinite_counter.h"
#include "ray_scene.h"
#include "volume/sdf_uniforms.h"
#include "uniforms.h"
#include "volume/occupancy.h"
#include "volume/volume_cascades.h"
#include "volume/volume_slots.h"
#include "volume/voxel_uniforms.h"
#include "volume/voxelizer.h"

namespace gis {

namespace {
std::string glslFloat(float v) {
    std::string s = std::to_string(v);
    return s.find('.') == std::string::npos ? s + ".0" : s;
}

template <class T>
void append(std::vector<T>& all, const std::vector<T>& more) {
    all.insert(all.end(), more.begin(), more.end());
}
}  // namespace

const std::vector<gl::UniformSlot>& uniformSlots() {
    static const std::vector<gl::UniformSlot> all = [] {
        std::vector<gl::UniformSlot> v;
        append(v, tableRows(kUniforms));
        append(v, tableRows(voxel::kVoxelUniforms));
        append(v, tableRows(emitters::kEmitterUniforms));
        append(v, tableRows(sdf::kSdfUniforms));
        append(v, tableRows(probes::kProbeUniforms));
        for (const ShaderTables& t : methodShaderTables()) append(v, t.uniforms);
        return v;
    }();
    return all;
}

const std::vector<gl::BindingSlot>& bindingSlots() {
    static const std::vector<gl::BindingSlot> all = [] {
        std::vector<gl::BindingSlot> v;
        append(v, tableRows(kBindings));
        append(v, tableRows(emitters::kEmitterBindings));
        append(v, tableRows(probes::kProbeBindings));
        append(v, tableRows(voxel::kVoxelBindings));
        append(v, tableRows(sdf::kSdfBindings));
        for (const ShaderTables& t : methodShaderTables()) append(v, t.bindings);
        return v;
    }();
    return all;
}

const std::vector<gl::UniformBlockDesc>& uniformBlocks() {
    static const std::vector<gl::UniformBlockDesc> all = [] {
        std::vector<gl::UniformBlockDesc> v{
            emitters::RestirBlock::desc(),
            voxel::ConeTraceBlock::desc(),
            voxel::VctDebugBlock::desc(),
            sdf::SdfMarchBlock::desc(),
            probes::ProbeUpdateBlock::desc(),
            probes::ProbeGatherBlock::desc(),
            probes::ProbeReflectBlock::desc(),
            SsaoBlock::desc(),
            SsaoTemporalBlock::desc(),
            EnvironmentBlock::desc(),
        };
        for (const ShaderTables& t : methodShaderTables()) append(v, t.blocks);
        return v;
    }();
    return all;
}

const std::vector<gl::StorageStructDesc>& storageStructs() {
    static const std::vector<gl::StorageStructDesc> all = {
        GpuLight::desc(),           BvhNode::desc(),     rays::TraceTriangle::desc(), rays::TriangleAttributes::desc(),
        rays::RayMaterial::desc(),  rays::Emitter::desc(),
    };
    return all;
}

const std::vector<std::pair<std::string, std::string>>& sharedShaderDefines() {
    static const std::vector<std::pair<std::string, std::string>> defines = [] {
        std::vector<std::pair<std::string, std::string>> d{
            {"MAX_HALF_FLOAT", glslFloat(gl::kMaxHalfFloat)},
            {"SDF_MAX_CASCADES", std::to_string(kMaxCascades)},
            {"SDF_HIT_THRESHOLD", glslFloat(sdf::kDefaultHitThreshold)},
            {"MAX_AO_KERNEL", std::to_string(kSsaoMaxKernel)},
            {"LIGHTS_BINDING", std::to_string(kLightsBinding)},
            {"BVH_NODES_BINDING", std::to_string(kBvhNodesBinding)},
            {"BVH_TRIANGLES_BINDING", std::to_string(kBvhTrianglesBinding)},
            {"RAY_ATTRIBUTES_BINDING", std::to_string(kRayAttributesBinding)},
            {"RAY_MATERIALS_BINDING", std::to_string(kRayMaterialsBinding)},
            {"RAY_EMITTERS_BINDING", std::to_string(kRayEmittersBinding)},
            {"RAY_COUNTS_BINDING", std::to_string(kRayCountsBinding)},
            {"OCC_BLOCK", std::to_string(kOccupancyBlock)},
            {"OCC_REGION", std::to_string(kOccupancyRegion)},
            {"OCC_BLOCKS_BINDING", std::to_string(kOccupancyBlocksBinding)},
            {"OCC_REGIONS_BINDING", std::to_string(kOccupancyRegionsBinding)},
            {"VOXEL_CHANNELS", std::to_string(kVoxelSumChannels)},
            {"VOXEL_PLACE_CHANNELS", std::to_string(kVoxelPlaceChannels)},
            {"VOXEL_SUMS_BINDING", std::to_string(kVoxelSumsBinding)},
            {"VOXEL_PLACES_BINDING", std::to_string(kVoxelPlacesBinding)},
            {"VOLUME_DISTANCE_UNIT", std::to_string(kVolumeDistanceUnit)},
            {"VOLUME_COARSE_UNIT", std::to_string(kVolumeCoarseUnit)},
            {"VOLUME_RADIANCE_UNIT", std::to_string(kVolumeRadianceUnit)},
            {"VOLUME_ALBEDO_UNIT", std::to_string(kVolumeAlbedoUnit)},
            {"VOLUME_EMISSION_UNIT", std::to_string(kVolumeEmissionUnit)},
            {"VOLUME_PUNCTUAL_UNIT", std::to_string(kVolumePunctualUnit)},
            {"VOLUME_SHADOW_MAPS_UNIT", std::to_string(kVolumeShadowMapsUnit)},
            {"VOLUME_SHADOW_CUBES_UNIT", std::to_string(kVolumeShadowCubesUnit)},
            {"VOLUME_HIT_LIGHTS_BINDING", std::to_string(kVolumeHitLightsBinding)},
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
        for (const gl::BindingSlot& b : bindingSlots()) d.emplace_back(b.name, std::to_string(b.point));
        for (const gl::UniformBlockDesc& b : uniformBlocks()) d.emplace_back(b.name, gl::glslBlockDeclaration(b));
        for (const gl::StorageStructDesc& s : storageStructs())
            d.emplace_back(std::string("STRUCT_") + s.name, gl::glslStructDeclaration(s));
        return d;
    }();
    return defines;
}

}  // namespace gis
