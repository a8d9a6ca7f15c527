#include "services/scene_services.h"

namespace gis {

RayScene& SceneServices::rays() {
    if (!rays_) rays_ = std::make_unique<RayScene>(scene, ledger, "scene.rays");
    return *rays_;
}

void SceneServices::invalidate(Changes changes) { volumes_.invalidate(changes); }

void SceneServices::lightsChanged() {
    if (rays_) rays_->updateLights(scene.cpu);
}

}  // namespace gis
