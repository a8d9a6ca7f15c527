#include "probes/screen_reflection.h"

#include <algorithm>
#include <cstdio>

#include "gl/dispatch.h"

namespace gis::probes {

namespace {
const ProgramDesc kProgram{"probe_screen_reflection", {"probes/screen_reflection.comp"}, {}};
const ProgramDesc kOccupancyProgram{"probe_screen_reflection_occupancy", {"probes/screen_reflection.comp"},
                                    {{"PROBE_TRACER_OCCUPANCY", "1"}}};
const ProgramDesc kEnvironmentProgram{"probe_screen_reflection_environment", {"probes/screen_reflection.comp"},
                                      {{"REFLECTION_ENVIRONMENT", "1"}}};
}  // namespace

std::vector<ProgramDesc> ScreenReflection::programs() { return {kProgram, kOccupancyProgram, kEnvironmentProgram}; }

int64_t ScreenReflection::bytes(int width, int height) { return 3 * int64_t(width) * height * 8; }

ScreenReflection::ScreenReflection(const gl::MemoryScope& scope, int width, int height, Tracer tracer)
    : block_(scope) {
    mean_ = gl::createTexture2D(scope, GL_RGBA16F, width, height);
    specular_ = gl::createTexture2D(scope, GL_RGBA16F, width, height);
    unseenMean_ = gl::createTexture2D(scope, GL_RGBA16F, width, height);
    program_ = buildProgram(tracer == Tracer::Occupancy ? kOccupancyProgram : kProgram);
    environmentProgram_ = buildProgram(kEnvironmentProgram);
}

bool ScreenReflection::settled() const {
    return live_.mode() == Reflection::Environment || framesAveraged_ >= live_.reflectionFrames;
}

Pass::Progress ScreenReflection::progress(Pass::Progress field, bool fieldConverged) const {
    if (live_.mode() == Reflection::Environment) return field;
    if (fieldConverged) field.done += std::min(framesAveraged_, live_.reflectionFrames);
    field.target += live_.reflectionFrames;
    return field;
}

std::string ScreenReflection::describe() const {
    if (live_.mode() == Reflection::Environment) return "reflection: the prefiltered environment (no rays)";
    char line[160];
    std::snprintf(line, sizeof line, "reflection: rays below roughness %.2g, %d per pixel, %d of %d frames averaged",
                  double(live_.reflectionRoughness), live_.reflectionRays, framesAveraged_, live_.reflectionFrames);
    return line;
}

namespace {
bool sameSettings(const ReflectionSettings& a, const ReflectionSettings& b) {
    return a.reflection == b.reflection && a.reflectionRoughness == b.reflectionRoughness &&
           a.reflectionRays == b.reflectionRays && a.reflectionFrames == b.reflectionFrames;
}
}  // namespace

void ScreenReflection::run(const Frame& frame, const ProbeField& field, const FieldSettings& live,
                           const gl::Texture& diffuse, const ReflectionSettings& s, bool changed,
                           float unseenIntensity) {
    if (changed || field.updatedLastFrame() || !sameSettings(s, live_)) framesAveraged_ = 0;
    live_ = s;
    const bool rays = s.mode() == Reflection::Rays;
    const GLuint p = rays ? program_.id() : environmentProgram_.id();
    frame.bindEnvironment();
    glUseProgram(p);
    if (rays) field.bindForHitLight(p, live);
    glProgramUniformMatrix4fv(p, UP_INV_VIEW_PROJ, 1, GL_FALSE, &frame.camera.invViewProj[0][0]);
    glProgramUniform3fv(p, UP_CAMERA_POS, 1, &frame.camera.position[0]);
    ProbeReflectBlock b;
    b.roughness = s.reflectionRoughness;
    b.rays = s.reflectionRays;
    b.framesAveraged = float(framesAveraged_);
    b.frame = frame_++;
    b.unseenIntensity = unseenIntensity;
    block_.set(b);
    glBindTextureUnit(TP_REFLECT_DEPTH, frame.texture(resource::kGbufferDepth));
    glBindTextureUnit(TP_REFLECT_NORMAL, frame.texture(resource::kGbufferNormal));
    glBindTextureUnit(TP_REFLECT_MATERIAL, frame.texture(resource::kGbufferMaterial));
    glBindImageTexture(IP_REFLECT_DIFFUSE, diffuse.id(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA16F);
    glBindImageTexture(IP_UNSEEN_MEAN, unseenMean_.id(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA16F);
    glBindImageTexture(IP_REFLECT_MEAN, mean_.id(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA16F);
    glBindImageTexture(IP_REFLECT_SPECULAR, specular_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    gl::dispatchCompute(gl::groupsFor(specular_.width, 8), gl::groupsFor(specular_.height, 8), 1, "probe reflection");
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
    if (!rays) return;
    field.releaseHitLight();
    ++framesAveraged_;
}

}  // namespace gis::probes
