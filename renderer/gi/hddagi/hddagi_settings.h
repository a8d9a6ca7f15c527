// HDDAGI's parameters: one row each in hddagiParams() (names that scripts and other checks use:
// hddagi.resolution, hddagi.cascades, hddagi.spacing, hddagi.rays, hddagi.half-res), defaults
// in the initialisers below. Where SDF GI has the same setting the default is the same, except the
// probe spacing and rays per probe (renderer/gi/hddagi/README.md says why).
#pragma once

#include "param_table.h"
#include "probes/probe_field.h"
#include "probes/screen_reflection.h"
#include "probes/screen_gather.h"

namespace gis {

// Its reflection members (hddagi.reflection*) come from probes::ReflectionSettings.
struct HddagiSettings : probes::ReflectionSettings {
    int resolution = 64;         // hddagi.resolution: voxels per cascade edge, a power of two (rebuild)
    int cascades = 0;            // hddagi.cascades: 0 = from the scene's extent, else 1..4 (rebuild)
    float cascadeExtent = 0.0f;  // hddagi.cascade-extent: the finest cascade's largest edge, world units, 0 = from the view (rebuild)
    float probeSpacing = 0.2f;   // hddagi.spacing: probe cell as a fraction of each cascade's extent (rebuild)
    int rays = 128;              // hddagi.rays: rays per probe per update (rebuild)
    int rayBudget = 0;           // hddagi.ray-budget: probe rays per frame, 0 = every due probe (rebuild)
    int storage = 1;             // hddagi.storage: sh1 | sh2 | octahedral (rebuild)
    bool halfResolution = true;  // hddagi.half-res: gather every 2x2 block's first pixel, upsample (rebuild)
    bool visibility = true;      // hddagi.visibility: Chebyshev visibility (live)
    bool pathTest = true;        // hddagi.path-test (live): the straight path walked through the occupancy
    bool bounces = true;         // hddagi.multibounce: probe rays' hits add the probes' irradiance (live)
    float hysteresis = 0.98f;    // hddagi.hysteresis (live)
    float threshold = 0.01f;     // hddagi.threshold (live)
    int maxUpdates = 100;        // hddagi.max-updates (live)
    float normalBias = 0.1f;     // hddagi.normal-bias (live)
    float intensity = 1.0f;      // hddagi.intensity: scales indirect.diffuse (live)
    // What the debug views show (live).
    int sliceAxis = 2;           // hddagi.slice-axis: x | y | z
    float slicePosition = 0.5f;  // hddagi.slice-position: 0..1 across the cascade
    int sliceCascade = 0;        // hddagi.slice-cascade (clamped to the count)
    int sliceLevel = 0;          // hddagi.slice-level: voxels | blocks | regions
    int stepsMax = 64;           // hddagi.steps-max: steps shown white in hddagi.steps

    probes::FieldSettings field() const;     // what the shared probe pipeline reads
    probes::GatherSettings gather() const;
    int gatherScale() const { return halfResolution ? 2 : 1; }
};

const ParamTable<HddagiSettings>& hddagiParams();
// What the ranges cannot say (a power-of-two resolution, a budget that pays for a probe); throws
// gis::Error naming the key.
void checkHddagiSettings(const HddagiSettings& s);

}  // namespace gis
