// The scene volumes of one renderer (SceneServices::volume): each built on its first request; the
// same request gets the same volume, so methods sharing a renderer share what they can.
#pragma once

#include <memory>
#include <vector>

#include "volume/scene_volume.h"

namespace gis {

class SceneVolumes {
public:
    // `bounds` is the scene's, read when a volume is built (after an edit, the edited scene's).
    // `rays`: the scene's ray scene, for volumes lit by the emitters.
    SceneVolumes(const Aabb& bounds, gl::MemoryLedger& ledger, RaySceneSource rays)
        : bounds_(bounds), ledger_(ledger), rays_(std::move(rays)) {}
    SceneVolume& get(const VolumeRequest& request);
    void invalidate(Changes changes);

private:
    const Aabb& bounds_;
    gl::MemoryLedger& ledger_;
    RaySceneSource rays_;
    std::vector<std::unique_ptr<SceneVolume>> volumes_;
};

}  // namespace gis
