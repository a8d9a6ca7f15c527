// The scene volumes of one renderer (SceneServices::volume): each built on its first request; the
// same request gets the same volume, so methods sharing a renderer share what they can.
#pragma once

#include <functional>
#include <limits>
#include <memory>
#include <vector>

#include "volume/scene_volume.h"

namespace gis {

class SceneVolumes {
public:
    // `bounds` is the scene's, read when a volume is built (after an edit, the edited scene's).
    // `rays`: the scene's ray scene, for volumes lit by the emitters. `viewDepth`: the render
    // camera's view depth, asked for only by volumes whose cascade count follows it.
    SceneVolumes(const Aabb& bounds, gl::MemoryLedger& ledger, RaySceneSource rays, std::function<float()> viewDepth)
        : bounds_(bounds), ledger_(ledger), rays_(std::move(rays)), viewDepth_(std::move(viewDepth)) {}
    SceneVolume& get(const VolumeRequest& request);
    void invalidate(Changes changes);

private:
    const Aabb& bounds_;
    gl::MemoryLedger& ledger_;
    RaySceneSource rays_;
    std::function<float()> viewDepth_;
    std::vector<std::unique_ptr<SceneVolume>> volumes_;
};

}  // namespace gis
