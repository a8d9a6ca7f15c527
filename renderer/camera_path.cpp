#include "camera_path.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace gis {

namespace {

// The keyframes as fractions of the bounds: x and z of the half extent about the centre, y of the
// height above the floor. In builtin:atrium (courtyard |x| < 10, |z| < 6 of bounds 13.3 x 9.3)
// they keep 1.5 m or more from the columns while the height swings between 2.1 and 4.6 m.
constexpr std::array<glm::vec3, CameraPath::kKeyframes> kKeyFractions{{
    {-0.50f, 0.25f, 0.40f},
    {0.00f, 0.42f, 0.48f},
    {0.52f, 0.30f, 0.38f},
    {0.55f, 0.55f, -0.32f},
    {0.00f, 0.30f, -0.46f},
    {-0.55f, 0.45f, -0.34f},
}};

// Uniform Catmull-Rom between p1 and p2 at u in [0, 1], and its derivative.
glm::vec3 catmullRom(const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2, const glm::vec3& p3, float u) {
    return 0.5f * (2.0f * p1 + (p2 - p0) * u + (2.0f * p0 - 5.0f * p1 + 4.0f * p2 - p3) * u * u +
                   (3.0f * p1 - p0 - 3.0f * p2 + p3) * u * u * u);
}
glm::vec3 catmullRomTangent(const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2, const glm::vec3& p3,
                            float u) {
    return 0.5f * ((p2 - p0) + 2.0f * (2.0f * p0 - 5.0f * p1 + 4.0f * p2 - p3) * u +
                   3.0f * (3.0f * p1 - p0 - 3.0f * p2 + p3) * u * u);
}

}  // namespace

CameraPose CameraPath::atParameter(float t) const {
    const float scaled = (t - std::floor(t)) * float(kKeyframes);
    const int segment = std::min(int(scaled), kKeyframes - 1);
    const float u = scaled - float(segment);
    auto key = [this](int i) { return keys_[size_t((i + kKeyframes) % kKeyframes)]; };
    const glm::vec3 p0 = key(segment - 1), p1 = key(segment), p2 = key(segment + 1), p3 = key(segment + 2);
    CameraPose pose;
    pose.position = catmullRom(p0, p1, p2, p3, u);
    pose.forward = glm::normalize(catmullRomTangent(p0, p1, p2, p3, u));
    return pose;
}

CameraPose CameraPath::at(int frame, int frames) const {
    if (frames < 1) throw Error("a fly-through needs at least one frame");
    return atParameter(float(frame % frames) / float(frames));
}

CameraPath flythroughPath(const Aabb& bounds) {
    if (bounds.empty()) throw Error("a fly-through needs a scene with geometry (its bounds are empty)");
    const glm::vec3 centre = bounds.center(), half = 0.5f * bounds.extent();
    std::array<glm::vec3, CameraPath::kKeyframes> keys;
    for (size_t i = 0; i < keys.size(); ++i) {
        const glm::vec3& f = kKeyFractions[i];
        keys[i] = {centre.x + f.x * half.x, bounds.min.y + f.y * bounds.extent().y, centre.z + f.z * half.z};
    }
    return CameraPath(keys);
}

CameraMatrices poseMatrices(const CameraPose& pose, const Aabb& bounds, float aspect) {
    const float diagonal = std::max(glm::length(bounds.extent()), 1e-3f);
    CameraMatrices m;
    m.position = pose.position;
    m.znear = 1e-3f * diagonal;
    m.zfar = 2.0f * diagonal;
    m.view = glm::lookAt(pose.position, pose.position + pose.forward, glm::vec3(0.0f, 1.0f, 0.0f));
    m.proj = glm::perspective(glm::radians(kFlythroughFovDegrees), aspect, m.znear, m.zfar);
    m.viewProj = m.proj * m.view;
    m.invViewProj = glm::inverse(m.viewProj);
    return m;
}

}  // namespace gis
