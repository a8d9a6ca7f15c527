// Voxel cone tracing's parameters: one row each in vctParams() (names that scripts and other
// checks use: vct.resolution, vct.conservative, vct.anisotropic, vct.bounces, ...), defaults in the
// initialisers below.
#pragma once

#include <string>

#include "param_table.h"
#include "scene/scene_lighting.h"  // kMaxFeedbackBounces
#include "volume/voxelizer.h"

namespace gis {

struct VctSettings {
    int resolution = 64;       // vct.resolution: voxels per edge, a power of two (rebuild)
    int conservative = 0;      // vct.conservative: auto | hardware | geometry | off (then ConservativeMode order; rebuild)
    bool anisotropic = true;   // vct.anisotropic: six directional mip chains (rebuild)
    int backfaces = 0;         // vct.backfaces: opaque | cull, what directional mips do with back faces (rebuild)
    int unlitOutsides = 0;     // vct.unlit-outsides: cull | keep, surfaces facing air no light reaches (rebuild)
    int bounces = 3;           // vct.bounces: 1 = direct light re-emitted once; more gather again (rebuild)
    bool feedback = false;     // vct.feedback: each update adds a bounce until converged (rebuild)
    int coneSet = 0;           // vct.cones: six (60-degree, Godot's) | four (90-degree) | many (32) (live)
    float stepFactor = 0.5f;   // vct.step: step as a fraction of the cone diameter (live)
    float maxDistance = 1.0f;  // vct.max-distance: fraction of the volume's edge (live)
    float offset = 1.5f;       // vct.offset: self-occlusion offset along the normal, voxels (live)
    float intensity = 1.0f;    // vct.intensity: scales the indirect terms (live)
    bool specular = true;      // vct.specular: trace the specular cone (live)
    float specularRoughness = 1.0f;  // vct.specular-roughness: rougher surfaces take the diffuse cones' result (live)
    // vct.sky-rays: rays per diffuse cone through the scene's triangles deciding how much of the
    // environment the cone sees; 0 = the cone's own transmittance through the voxels (live)
    int skyRays = 1;
    int traceScale = 0;        // vct.trace-scale: 1 | 2 | 4 full-resolution pixels per traced texel per axis (rebuild)
    // What the debug views vct.voxels and vct.slice show (live).
    int debugChannel = 0;      // vct.debug-channel: albedo | emission | radiance | occupancy
    int debugLevel = 0;        // vct.debug-level: mip level (radiance and occupancy)
    int sliceAxis = 2;         // vct.slice-axis: x | y | z
    float slicePosition = 0.5f;  // vct.slice-position: 0..1 across the volume

    // auto is the hardware path where the driver has it, else geometry, silently: only a user who
    // asked for `hardware` is told it fell back (issue #42: every llvmpipe run warned).
    ConservativeMode conservativeMode() const {
        return conservative == 0 ? ConservativeMode::Hardware : ConservativeMode(conservative - 1);
    }
    bool conservativeAsked() const { return conservative != 0; }
    int tracePixels() const { return 1 << traceScale; }  // full-resolution pixels per traced texel per axis
    // Frames a static view takes to reach the full-resolution result: one per jitter phase of a
    // traced texel (one frame without reduced-resolution tracing).
    int framesToFullResolution() const { return tracePixels() * tracePixels(); }
    // With feedback, at most kMaxFeedbackBounces more: the pass stops earlier for darker scenes.
    int framesToConverge() const { return framesToFullResolution() + (feedback ? kMaxFeedbackBounces - 1 : 0); }
};

struct VolumeRequest;
// What VCT asks of the scene volume (renderer/volume/) for these settings.
VolumeRequest vctVolumeRequest(const VctSettings& s);
// The largest vct.resolution whose volume, in its smallest form (no directional mips, one bounce),
// fits kVoxelBudgetBytes: the row's maximum, so what is listed can be allocated.
int maxVctResolution();

const ParamTable<VctSettings>& vctParams();
// What the table's ranges cannot say (a power-of-two resolution); throws gis::Error naming the key.
void checkVctSettings(const VctSettings& s);

}  // namespace gis
