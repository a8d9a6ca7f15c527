// What several GI methods need from the scene, built lazily once per renderer rather than once
// per pass: the ray-tracing scene (Embree BVH, triangles, materials, emitters), and the scene's
// bounds with a helper that fits volumes to them. Charged to "scene.*" owners in the ledger.
#pragma once

#include <memory>

#include "debug_view.h"
#include "gpu_scene.h"
#include "ray_scene.h"

namespace gis {

struct SceneServices {
    SceneServices(const GpuScene& scene, gl::MemoryLedger& ledger) : scene(scene), ledger(ledger) {}
    const GpuScene& scene;
    gl::MemoryLedger& ledger;

    // The BVH and ray-tracing buffers: built on first use (about 14 ms for DamagedHelmet).
    RayScene& rays();
    bool hasRays() const { return rays_ != nullptr; }
    const Aabb& bounds() const { return scene.cpu.bounds; }
    // The scene's lights were edited: every service that holds them uploads them again.
    void lightsChanged();
    // The program debug views draw frame textures with (renderer/debug_view.h).
    ChannelDisplay& channelDisplay();

private:
    std::unique_ptr<RayScene> rays_;
    std::unique_ptr<ChannelDisplay> channelDisplay_;
};

}  // namespace gis
