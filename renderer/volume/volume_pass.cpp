#include "volume/volume_pass.h"

namespace gis {

std::vector<std::string> VolumePass::inputs() const {
    std::vector<std::string> all = ownInputs();
    for (const std::string& name : SceneVolume::inputs()) all.push_back(name);
    return all;
}

void VolumePass::execute(Frame& frame) {
    volume_->update(frame, bounceCones(frame));
    run(frame);
}

}  // namespace gis
