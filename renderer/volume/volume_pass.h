// A pass that reads the scene volume (volume/scene_volume.h). The method states its VolumeRequest
// once (SceneServices::volume) and hands the volume to this base; the volume's inputs join the
// pass's own, and the volume is brought up to date for the frame before the pass's own work, under
// the pass's step timers ("voxelize", "inject", ...). The method binds the volume into its
// programs with SceneVolume::bind() and lists SceneVolume::programs() among its own.
#pragma once

#include <string>
#include <vector>

#include "frame.h"
#include "volume/scene_volume.h"

namespace gis {

class VolumePass : public Pass {
public:
    std::vector<std::string> inputs() const final;
    void execute(Frame& frame) final;
    const SceneVolume& volume() const { return *volume_; }

protected:
    explicit VolumePass(SceneVolume& volume) : volume_(&volume) {}
    // The frame resources the method's own work reads, besides the volume's.
    virtual std::vector<std::string> ownInputs() const = 0;
    // The method's own work, once the volume is up to date.
    virtual void run(Frame& frame) = 0;
    // The cones the volume's further bounces gather with: the method's live setting (VCT's).
    virtual ConeSettings bounceCones(const Frame&) const { return {}; }
    SceneVolume* volume_;  // the renderer's, shared (SceneServices)
};

}  // namespace gis
