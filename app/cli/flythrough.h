// Camera motion measured: the scripted fly-through (renderer/camera_path.h) rendered frame by
// frame, each frame's GPU and wall-clock time and which of the scene volume's cascades it rebuilt
// (a cascade that follows the camera is rebuilt whole when it moves: its voxelize step runs).
// `render --flythrough` prints the frames, `bench --flythrough` keeps their summary in its row.
#pragma once

#include <string>
#include <vector>

#include "scene/scene.h"

namespace gis {

class Renderer;

struct FlythroughFrame {
    double gpuMs = 0.0;                 // every pass's GPU time in this frame
    double wallMs = 0.0;                // wall clock with glFinish
    std::vector<std::string> rebuilt;   // the voxelize steps that ran ("sdf/c0.voxelize"): cascades rebuilt
};

// Renders one warm-up frame at the path's first pose (it builds what every later frame reuses:
// shadow maps, the volume; not returned), then the `frames` frames of the path fitted to `bounds`.
std::vector<FlythroughFrame> flyThrough(Renderer& renderer, const Aabb& bounds, int frames);

struct FlythroughStats {
    int frames = 0;
    double medianMs = 0.0, worstMs = 0.0;   // GPU ms per frame
    double medianWallMs = 0.0;
    int moveFrames = 0;                      // frames that rebuilt a cascade
    // GPU ms medians of the frames that rebuilt a cascade and of the others; -1 where there is none.
    double moveMedianMs = -1.0, stillMedianMs = -1.0;
};
FlythroughStats summarizeFlythrough(const std::vector<FlythroughFrame>& frames);

// The frames and their summary as `render --flythrough --timings` prints them.
void printFlythrough(const std::vector<FlythroughFrame>& frames);

}  // namespace gis
