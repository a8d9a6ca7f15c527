#include "services/scene_services.h"

namespace gis {

RayScene& SceneServices::rays() {
    if (!rays_) rays_ = std::make_unique<RayScene>(scene, ledger, "scene.rays");
    return *rays_;
}

float SceneServices::viewDepth() {
    if (!viewDepth_) viewDepth_ = nearViewDepth(rays_ ? rays_->bvh : buildBvh(scene.cpu), camera_);
    return *viewDepth_;
}

void SceneServices::invalidate(Changes changes) {
    if (changes & ChangeGeometry) {
        air_ = sceneAirBounds(scene.cpu);
        viewDepth_.reset();
    }
    volumes_.invalidate(changes);
}

void SceneServices::lightsChanged() {
    if (rays_) rays_->updateLights(scene.cpu);
}

}  // namespace gis
