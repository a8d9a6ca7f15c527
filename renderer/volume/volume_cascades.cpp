#include "volume/volume_cascades.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "bvh.h"


namespace gis {

int chooseCascadeCount(const VolumeFit& sceneCube, float finestExtent, int requested, const std::string& method) {
    if (requested < 0 || requested > kMaxCascades)
        throw Error(method + ".cascades " + std::to_string(requested) + " is out of range [0 (auto), " +
                    std::to_string(kMaxCascades) + "]");
    if (requested > 0) return requested;
    if (!(finestExtent > 0.0f))  // +inf (a view that sees nothing of the scene) gets one volume
        throw Error(method + ".cascade-extent must be a positive number of world units, or 0 for one from the view");
    if (sceneCube.size <= finestExtent) return 1;
    const int halvings = int(std::ceil(std::log2(double(sceneCube.size) / double(finestExtent))));
    return std::clamp(1 + halvings, 1, kMaxCascades);
}

glm::ivec3 CascadeLayout::centredOffset(int i, const glm::vec3& camera) const {
    const int n = scene.resolution;
    const int span = n << (count - 1 - i);  // the scene cube's edge in cascade i's cells
    const glm::vec3 centre = (camera - scene.origin) / cellSize(i) - glm::vec3(0.5f * float(n));
    glm::ivec3 o;
    for (int a = 0; a < 3; ++a) {
        const float c = std::isfinite(centre[a]) ? std::clamp(centre[a], -1e9f, 1e9f) : 0.0f;
        o[a] = std::clamp(int(std::lround(c)), 0, span - n);
    }
    return o;
}

bool CascadeLayout::mustMove(const glm::ivec3& current, const glm::ivec3& centred) const {
    const glm::ivec3 d = glm::abs(centred - current);
    return std::max({d.x, d.y, d.z}) > snapCells();
}

SdfVolume CascadeLayout::volume(int i, const glm::ivec3& offset) const {
    return {scene.origin + glm::vec3(offset) * cellSize(i), extent(i), scene.resolution};
}

CascadeLayout layoutCascades(const Aabb& bounds, int resolution, float finestExtent, int requested,
                             const std::string& method, float marginVoxels) {
    CascadeLayout layout;
    layout.scene = fitVolume(bounds, resolution, marginVoxels);
    layout.count = chooseCascadeCount(layout.scene, finestExtent, requested, method);
    return layout;
}

float nearViewDepth(const Bvh& bvh, const CameraMatrices& camera) {
    auto unproject = [&](float x, float y, float z) {
        const glm::vec4 p = camera.invViewProj * glm::vec4(x, y, z, 1.0f);
        return glm::vec3(p) / p.w;
    };
    std::vector<float> depths;
    for (int j = 0; j < kViewDepthRays; ++j)
        for (int i = 0; i < kViewDepthRays; ++i) {
            const float x = (float(i) + 0.5f) / float(kViewDepthRays) * 2.0f - 1.0f;
            const float y = (float(j) + 0.5f) / float(kViewDepthRays) * 2.0f - 1.0f;
            // From the near plane along the pixel's line: a perspective camera's rays leave its
            // position, an orthographic one's are parallel. z = 0 is finite with an infinite far plane.
            const glm::vec3 near = unproject(x, y, -1.0f), mid = unproject(x, y, 0.0f);
            const glm::vec3 dir = glm::normalize(mid - near);
            if (!std::isfinite(dir.x + dir.y + dir.z)) continue;
            // Along the ray from the camera's plane: its position for a perspective camera, its
            // plane through the pixel for an orthographic one.
            depths.push_back(std::max(0.0f, glm::dot(near - camera.position, dir)) + nearestHit(bvh, near, dir));
        }
    if (depths.empty()) return std::numeric_limits<float>::infinity();
    const size_t k = depths.size() / kNearViewFraction;
    std::nth_element(depths.begin(), depths.begin() + std::ptrdiff_t(k), depths.end());
    return depths[k];
}

float finestCascadeExtent(float cascadeExtent, float viewDepth) {
    return cascadeExtent > 0.0f ? cascadeExtent : kFinestExtentPerViewDepth * viewDepth;
}

}  // namespace gis
