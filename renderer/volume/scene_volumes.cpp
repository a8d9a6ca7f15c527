#include "volume/scene_volumes.h"

namespace gis {

SceneVolume& SceneVolumes::get(const VolumeRequest& request) {
    for (const auto& v : volumes_)
        if (v->request() == request) return *v;
    const float depth = request.countFromView() ? viewDepth_() : std::numeric_limits<float>::infinity();
    volumes_.push_back(std::make_unique<SceneVolume>(bounds_, request, depth, ledger_, rays_));
    return *volumes_.back();
}

void SceneVolumes::invalidate(Changes changes) {
    for (const auto& v : volumes_) v->invalidate(changes);
}

}  // namespace gis
