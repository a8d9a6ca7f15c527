// A scripted camera path: the fly-through `render --flythrough` and `bench --flythrough` measure
// camera motion with. A closed, uniform Catmull-Rom spline through six keyframes placed in the
// scene's bounds as fractions of its extent (for builtin:atrium: a loop round the courtyard
// between 2 and 4.6 m up, rising and falling), the camera looking along the spline's tangent.
// Pure functions of the bounds and the frame index (no clock, no state), so every run, and every
// method that wants the same motion, sees the same poses. No GL.
#pragma once

#include <array>

#include <glm/glm.hpp>

#include "render_settings.h"
#include "scene/scene.h"

namespace gis {

// The frame count of the fly-through the bench and the issue measure (#24).
constexpr int kFlythroughFrames = 60;

struct CameraPose {
    glm::vec3 position{0.0f};
    glm::vec3 forward{0.0f, 0.0f, -1.0f};  // unit length, never vertical (up is +Y)
};

class CameraPath {
public:
    static constexpr int kKeyframes = 6;
    explicit CameraPath(const std::array<glm::vec3, kKeyframes>& keyframes) : keys_(keyframes) {}
    // The pose of `frame` of a fly-through of `frames` frames: frame 0 at the first keyframe, the
    // loop covered once, frame `frames` would be frame 0 again.
    CameraPose at(int frame, int frames) const;
    // At t in [0, 1) along the loop.
    CameraPose atParameter(float t) const;
    const std::array<glm::vec3, kKeyframes>& keyframes() const { return keys_; }

private:
    std::array<glm::vec3, kKeyframes> keys_;
};

// The fly-through fitted to `bounds` (throws gis::Error for empty bounds).
CameraPath flythroughPath(const Aabb& bounds);

// The view and projection of `pose`: +Y up, a vertical field of view of kFlythroughFovDegrees,
// near and far planes from the bounds' diagonal.
constexpr float kFlythroughFovDegrees = 60.0f;
CameraMatrices poseMatrices(const CameraPose& pose, const Aabb& bounds, float aspect);

}  // namespace gis
