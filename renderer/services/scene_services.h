// What several GI methods need from the scene, built lazily once per renderer rather than once
// per pass: the ray-tracing scene (Embree BVH, triangles, materials, emitters; charged to
// "scene.rays") and the scene volume (voxels, distance field, their light and cascades; charged to
// the method that asked, so its row shows its whole footprint).
#pragma once

#include <memory>
#include <optional>

#include "gpu_scene.h"
#include "ray_scene.h"
#include "volume/scene_volumes.h"

namespace gis {

struct SceneServices {
    // `camera`: the render's (its settings'), whose view the volumes' cascade count may follow.
    SceneServices(const GpuScene& scene, gl::MemoryLedger& ledger, const CameraMatrices& camera)
        : scene(scene), ledger(ledger), camera_(camera), air_(sceneAirBounds(scene.cpu)),
          volumes_(air_, ledger, [this]() -> RayScene& { return rays(); }, [this] { return viewDepth(); }) {}
    const GpuScene& scene;
    gl::MemoryLedger& ledger;

    // The BVH and ray-tracing buffers: built on first use (about 14 ms for DamagedHelmet).
    RayScene& rays();
    bool hasRays() const { return rays_ != nullptr; }
    // The render camera's near view depth (volume/volume_cascades.h): traced on first use, with
    // the ray scene's BVH when there is one; again after a geometry edit.
    float viewDepth();
    const Aabb& bounds() const { return scene.cpu.bounds; }
    // The bounds with air outside each face behind which the scene is solid (volume/volume_fit.h:
    // sceneAirBounds): what the scene volumes are fitted to, so one model gets the space around
    // it that its sky and bounce light arrive through. Worked out again after a geometry edit.
    const Aabb& airBounds() const { return air_; }
    // The scene volume as `request` describes it: built on first use; the same request gets the
    // same volume, so methods sharing a renderer share what they can.
    SceneVolume& volume(const VolumeRequest& request) { return volumes_.get(request); }
    // What changed, for the services that cache anything derived from it (the volumes).
    void invalidate(Changes changes);
    // The scene's lights were edited: every service that holds them uploads them again.
    void lightsChanged();

private:
    std::unique_ptr<RayScene> rays_;
    CameraMatrices camera_;
    std::optional<float> viewDepth_;
    Aabb air_;   // before volumes_, which keep a reference to it
    SceneVolumes volumes_;
};

}  // namespace gis
