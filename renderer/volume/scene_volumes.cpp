#include "volume/scene_volumes.h"

namespace gis {

SceneVolume& SceneVolumes::get(const VolumeRequest& request) {
    for (const auto& v : volumes_)
        if (v->request() == request) return *v;
    volumes_.push_back(std::make_unique<SceneVolume>(bounds_, request, ledger_, rays_));
    return *volumes_.back();
}

void SceneVolumes::invalidate(Changes changes) {
    for (const auto& v : volumes_) v->invalidate(changes);
}

}  // namespace gis
