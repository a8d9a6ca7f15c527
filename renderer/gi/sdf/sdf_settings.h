// SDF GI's parameters: one row each in sdfParams() (names that scripts and other checks use:
// sdf.resolution, sdf.jfa, sdf.diffuse, sdf.rays, sdf.probe-ray-budget), defaults in the initialisers below.
#pragma once

#include "param_table.h"
#include "probes/probe_field.h"
#include "probes/screen_reflection.h"
#include "volume/distance_field.h"

namespace gis {

// indirect.specular's members (sdf.reflection*) come from probes::ReflectionSettings: with the
// probes, the shared screen reflection; with sdf.diffuse=rays, a mirror ray of its own below
// sdf.reflection-roughness (reflection-rays and -frames are the screen reflection's alone).
struct SdfGiSettings : probes::ReflectionSettings {
    int resolution = 64;        // sdf.resolution: cells per edge of the voxel grid and the field (rebuild)
    int jfa = 2;                // sdf.jfa: plain | 1+jfa | jfa+2 (JfaVariant order; rebuild)
    int cascades = 0;           // sdf.cascades: 0 = from the scene's extent, else 1..4 (rebuild)
    float cascadeExtent = 0.0f; // sdf.cascade-extent: the finest cascade's largest edge, world units, 0 = from the view (rebuild)
    int bounces = 1;            // sdf.bounces: 1 = hits see direct light and emission; more gather again (rebuild)
    int diffuse = 0;            // sdf.diffuse: probes (SDFGI's gather) | rays (per pixel) (rebuild)
    // sdf.probe-spacing: probe cell as a fraction of each cascade's extent (rebuild): SDFGI's fraction. Twice
    // it left a building's corridor in the finest cascade with hardly a probe (README, "Probe spacing").
    float probeSpacing = 0.125f;
    // sdf.probe-rays: rays per probe per update (rebuild). A pixel reads 8 probes, each averaged over its
    // updates: this many score as four times as many at this spacing (README, "Probe spacing").
    int probeRays = 32;
    int rayBudget = 0;          // sdf.probe-ray-budget: probe rays per frame, 0 = every due probe (rebuild)
    bool pathTest = true;       // sdf.probe-path-test: the probe gather's straight-path test (rebuild)
    int traceScale = 1;         // sdf.trace-scale: 1 | 2 | 4 full-resolution pixels per traced pixel per axis, the
                                // choice's index (1: half resolution) (rebuild)
    int rays = 4;               // sdf.rays: cosine-distributed diffuse rays per traced pixel per frame (live)
    int maxSteps = 64;          // sdf.max-steps: marcher steps before a ray counts as a miss (live)
    float relaxation = 1.2f;    // sdf.relaxation: over-relaxed step factor (live)
    float hitThreshold = sdf::kDefaultHitThreshold;  // sdf.hit-threshold: |distance| below this many cells is a hit, pixels' and probes' rays
    float offset = 1.5f;        // sdf.offset: rays start this many cells above the surface (live)
    float temporal = 0.9f;      // sdf.temporal: largest weight of the reprojected history (live)
    int filterRadius = 2;       // sdf.filter-radius: edge-aware filter half-width, traced pixels (live)
    // sdf.ao: strength of the near-field soft occlusion written to "ao" (live). Off by default: the
    // probes' Chebyshev visibility already occludes their light, and the extra darkening made every
    // comparison with Cycles and the path tracer worse (README, "sdf.ao", scripts/sdf-ao-table.sh).
    float aoStrength = 0.0f;
    float intensity = 1.0f;     // sdf.intensity: scales the indirect terms (live)
    // What the debug views show (live).
    int sliceAxis = 2;          // sdf.slice-axis: x | y | z
    float slicePosition = 0.5f; // sdf.slice-position: 0..1 across the volume
    int sliceCascade = 0;       // sdf.slice-cascade: which cascade sdf.slice cuts (clamped to the count)

    JfaVariant jfaVariant() const { return JfaVariant(jfa); }
    bool probeGather() const { return diffuse == 0; }
    int tracePixels() const { return 1 << traceScale; }  // full-resolution pixels per traced pixel per axis
    probes::FieldSettings probeField() const;  // what the shared probe pipeline reads
};

const ParamTable<SdfGiSettings>& sdfParams();

struct VolumeRequest;
// What SDF GI asks of the scene volume: voxels, their light and the distance field, in cascades
// around the camera for a large scene.
VolumeRequest sdfVolumeRequest(const SdfGiSettings& s);
// The largest sdf.resolution whose volume fits the voxel budget (one cascade, one bounce: the
// least a volume of that size holds), so the listed range holds only what can be allocated.
int maxSdfResolution();

}  // namespace gis
