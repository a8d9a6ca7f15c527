#include "services/scene_services.h"

namespace gis {

RayScene& SceneServices::rays() {
    if (!rays_) rays_ = std::make_unique<RayScene>(scene, ledger, "scene.rays");
    return *rays_;
}

SceneVolume& SceneServices::volume(const VolumeRequest& request) {
    for (const auto& v : volumes_)
        if (v->request() == request) return *v;
    volumes_.push_back(std::make_unique<SceneVolume>(scene.cpu.bounds, request, ledger));
    return *volumes_.back();
}

void SceneServices::invalidate(Changes changes) {
    for (const auto& v : volumes_) v->invalidate(changes);
}

void SceneServices::lightsChanged() {
    if (rays_) rays_->updateLights(scene.cpu);
}

}  // namespace gis
