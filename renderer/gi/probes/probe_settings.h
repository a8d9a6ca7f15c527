// Probe GI's parameters: one row each in probeParams() (names that scripts and other checks use:
// probes.spacing, probes.rays, probes.storage, probes.visibility, probes.ray-budget), defaults in
// the initialisers below.
#pragma once

#include "param_table.h"
#include "probes/probe_field.h"
#include "probes/screen_reflection.h"

namespace gis {

// Its reflection members (probes.reflection*) come from probes::ReflectionSettings.
struct ProbeSettings : probes::ReflectionSettings {
    // probes.spacing (rebuild): cell width as a fraction of each cascade's extent (the coarsest: the
    // scene's); an eighth, as SDF GI's since issue #39: a quarter of the building's finest cascade
    // put its probes 1.36 m apart, in and behind the corridor's walls. probes.rays (rebuild: sizes
    // the ray buffer): 32 pay for the eighth's 8x the probes at about the quarter's cost.
    float spacing = 0.125f;
    int rays = 32;
    int storage = 1;            // probes.storage: sh1 | sh2 | octahedral (rebuild)
    bool visibility = true;     // probes.visibility: Chebyshev visibility from the distance moments (live)
    // probes.path-test (live): on; with a grid per cascade a room near the camera holds probes of
    // its own, and the probes outside it no longer light it through its walls.
    bool pathTest = true;
    int rayBudget = 0;          // probes.ray-budget: probe rays per frame, most urgent probes first, 0 = all due (rebuild)
    int sdfResolution = 64;     // probes.sdf-resolution: voxels and distance-field cells per edge of each cascade (rebuild)
    // probes.cascades, probes.cascade-extent (rebuild): the volume in cascades around the camera,
    // each with its probe grid, so a 20 cm wall near the camera is resolved by both.
    int cascades = 0;
    float cascadeExtent = 0.0f;
    int inside = 0;             // probes.inside: relocate | off, for probes inside solid geometry (rebuild)
    bool bounces = true;        // probes.multibounce: ray hits also get the probes' own irradiance (live)
    float hysteresis = 0.98f;   // probes.hysteresis: weight of the old value once warmed up (live)
    float threshold = 0.01f;    // probes.threshold: relative change below which updates stop (live)
    int maxUpdates = 100;       // probes.max-updates: updates per probe after which they stop anyway (live)
    float normalBias = 0.1f;    // probes.normal-bias: along the normal and towards the eye, x probe step (live)
    int gatherScale = 0;        // probes.gather-scale: 1 | 2 | 4 pixels per gathered pixel, upsampled (rebuild)
    float intensity = 1.0f;     // probes.intensity: scales indirect.diffuse (live)
    int debugProbe = -1;        // probes.debug-probe: whose rays probes.rays draws; -1 = the middle one (live)
    probes::Storage storageKind() const { return probes::Storage(storage); }
    probes::FieldSettings field() const;  // what the shared probe pipeline reads
    int gatherPixels() const { return 1 << gatherScale; }  // full-resolution pixels per gathered one, per axis
};

const ParamTable<ProbeSettings>& probeParams();
// What the ranges cannot say (a power-of-two resolution); throws gis::Error naming the key.
void checkProbeSettings(const ProbeSettings& s);

}  // namespace gis
