#include "volume/volume_fit.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

namespace gis {

glm::mat4 VolumeFit::worldToVoxelMatrix() const {
    return glm::scale(glm::mat4(1.0f), glm::vec3(1.0f / voxelSize())) * glm::translate(glm::mat4(1.0f), -origin);
}

glm::mat4 VolumeFit::voxelToWorldMatrix() const {
    return glm::translate(glm::mat4(1.0f), origin) * glm::scale(glm::mat4(1.0f), glm::vec3(voxelSize()));
}

VolumeFit fitVolume(const Aabb& bounds, int resolution, float marginVoxels) {
    if (resolution < 1 || resolution > 4096)
        throw Error("volume resolution " + std::to_string(resolution) + " is out of range [1, 4096]");
    if (!std::isfinite(marginVoxels) || marginVoxels < 0.0f || 2.0f * marginVoxels >= float(resolution))
        marginVoxels = 0.0f;  // a tiny grid cannot spare voxels for a margin
    VolumeFit f;
    f.resolution = resolution;
    if (bounds.empty()) {
        f.origin = glm::vec3(-0.5f);
        f.size = 1.0f;
        return f;
    }
    for (int c = 0; c < 3; ++c)
        if (!std::isfinite(bounds.min[c]) || !std::isfinite(bounds.max[c]))
            throw Error("cannot fit a volume to non-finite scene bounds");
    const glm::vec3 center = bounds.center();
    const glm::vec3 extent = bounds.extent();
    float longest = std::max({extent.x, extent.y, extent.z});
    // A point-like scene: size it from where it is, so float voxel coordinates stay meaningful.
    const float magnitude = std::max({std::abs(center.x), std::abs(center.y), std::abs(center.z)});
    const float floorSize = std::max(magnitude * 1e-4f, 1e-30f);
    longest = std::max(longest, floorSize);
    // The cube holds `resolution - 2 * margin` voxels of scene and `margin` empty ones each side.
    f.size = longest * float(resolution) / (float(resolution) - 2.0f * marginVoxels);
    f.origin = center - glm::vec3(0.5f * f.size);
    return f;
}

}  // namespace gis
