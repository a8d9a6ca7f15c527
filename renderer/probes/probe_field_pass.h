// The pass of a method built on the probe field (probes, hddagi): probes over the scene volume's
// cascades (probe_field.h), gathered per pixel into "indirect.diffuse" (screen_gather.h), with
// reflection rays walked and shaded as the probes' own into "indirect.specular"
// (screen_reflection.h). The method states its volume, its settings, its stats and its debug
// views; the frame's work is this pass's. A static view with converged probes costs nothing
// (settled()); a change restarts the probes, and the volume rebuilds what the change touched.
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "probes/probe_field.h"
#include "probes/screen_gather.h"
#include "probes/screen_reflection.h"
#include "volume/volume_pass.h"

namespace gis::probes {

// What a method fixes when its pass is built: its volume, its probes' spacing and field, and the
// full-resolution pixels per gathered one (per axis).
struct ProbeFieldShape {
    VolumeRequest volume;
    float spacing = 0.0f;
    FieldSettings field;
    int gatherPixels = 1;
};

// What a method's live settings say to the field, the gather and the reflection each frame.
struct ProbeFieldLive {
    FieldSettings field;
    GatherSettings gather;
    ReflectionSettings reflection;
};

class ProbeFieldPass : public VolumePass {
public:
    const char* name() const override { return name_; }
    std::vector<std::string> ownInputs() const override;
    std::vector<std::string> outputs() const override;
    bool settled() const override { return field_->converged() && !changed_ && reflection_->settled(); }
    // Updates as progress, so `render` (and the sandbox's "converge") renders until the probes have
    // converged: done = updates read back, target = the most updates there can be, and both the
    // updates done once no probe is due any more.
    Progress progress() const override { return reflection_->progress(field_->progress(), field_->converged()); }
    void invalidate(Changes c) override;
    bool writesImagesOrBuffers() const override { return true; }
    std::optional<RayCounts> raysTraced() const override { return field_->raysTraced(); }
    const ProbeField& field() const { return *field_; }  // what tests and the bench look at

    // Every program the method's pass may build: the volume's, the field's, the gather's, the reflection's.
    static std::vector<ProgramDesc> programs(const VolumeRequest& volume);
    // GPU bytes by part, each part named after `method`, as SceneServices will fit the volume.
    static std::vector<std::pair<std::string, uint64_t>> estimateMemory(const std::string& method, const Scene& scene,
                                                                        const RenderSettings& settings,
                                                                        const ProbeFieldShape& shape);

protected:
    // `volume` is the one SceneServices fitted for shape.volume; `sceneBounds` what it was fitted to.
    ProbeFieldPass(const char* name, SceneVolume& volume, gl::MemoryLedger& ledger, const Aabb& sceneBounds,
                   const RenderSettings& settings, const ProbeFieldShape& shape);
    virtual ProbeFieldLive live(const RenderSettings& settings) const = 0;
    void run(Frame& frame) final;
    // The lines every probe-field method's stats begin with (the field's) and end with (its cascades', the reflection's).
    std::vector<std::string> stats(const std::string& volumeLine) const;

    std::unique_ptr<ProbeField> field_;

private:
    const char* name_;
    Aabb sceneBounds_;
    float spacing_;
    std::unique_ptr<ScreenGather> gather_;
    std::unique_ptr<ScreenReflection> reflection_;
    bool changed_ = true;  // something arrived through invalidate() since the last run
};

}  // namespace gis::probes
