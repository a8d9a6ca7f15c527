#include "gi/sdf/sdf_settings.h"

#include "probes/probe_params.h"
#include "volume/scene_volume.h"
#include "volume/cascade_params.h"
#include "volume/volume_cascades.h"

namespace gis {

VolumeRequest sdfVolumeRequest(const SdfGiSettings& s) {
    VolumeRequest r;
    r.method = "sdf";
    r.resolution = s.resolution;
    r.resolutionKey = "sdf.resolution";
    r.bounces = s.bounces;
    r.distanceField = true;
    r.jfa = s.jfaVariant();
    r.albedoAtlas = s.probeGather();  // the probes' rays light their hits' multi-bounce by it
    r.cascades = s.cascades;
    r.cascadeExtent = s.cascadeExtent;
    return r;
}

int maxSdfResolution() {
    static const int largest = [] {
        SdfGiSettings s;
        s.bounces = 1;
        auto fits = [&](int n) {
            s.resolution = n;
            return sceneVolumeBytes(sdfVolumeRequest(s), 1) <= kVoxelBudgetBytes;
        };
        int lo = 8, hi = 4096;  // fits(lo); the answer is below hi
        while (hi - lo > 1) (fits((lo + hi) / 2) ? lo : hi) = (lo + hi) / 2;
        return lo;
    }();
    return largest;
}

const ParamTable<SdfGiSettings>& sdfParams() {
    using S = SdfGiSettings;
    using U = ParamUpdate;
    static const ParamTable<S> table = [] {
        ParamTable<S> t;
        t.integer(&S::resolution, "resolution", "Resolution",
                 "cells per edge of the voxel grid and the distance field (one more than the largest would exceed "
                 "the " + std::to_string(kVoxelBudgetBytes >> 30) + " GiB a voxel method may hold)",
                 8, maxSdfResolution(), U::Rebuild)
        .choice(&S::jfa, "jfa", "Jump flood", "plain JFA, or with a step-1 pass first (1+jfa) or steps 2 and 1 after (jfa+2)",
                {"plain", "1+jfa", "jfa+2"}, U::Rebuild);
        addCascadeRows(t, "sdf");
        t.integer(&S::bounces, "bounces", "Bounces",
                 "1 = ray hits see direct light and emission; more gather in voxel space again", 1, 4, U::Rebuild)
        .choice(&S::diffuse, "diffuse", "Diffuse from",
                "probes = SDFGI: a probe grid per cascade, traced through the field and gathered per pixel; rays = "
                "cosine rays per traced pixel, accumulated over frames and filtered",
                {"probes", "rays"}, U::Rebuild);
        probes::addGridRows(t, "probe-", {&S::probeSpacing, &S::probeRays, &S::rayBudget});
        t.boolean(&S::pathTest, "probe-path-test", "Probe path test", probes::kPathTestHelp, ParamUpdate::Rebuild);
        t.choice(&S::traceScale, "trace-scale", "Trace scale",
                "full-resolution pixels per traced pixel per axis: the probe gather, mirror ray and occlusion (with "
                "sdf.diffuse=rays the diffuse rays) run for one pixel per block and are filtered back up",
                {"1", "2", "4"}, U::Rebuild)
        .integer(&S::rays, "rays", "Rays per pixel",
                 "cosine-distributed diffuse rays per traced pixel and frame (sdf.diffuse=rays; with probes, a "
                 "pixel's that sees none of them)", 1,
                 64, U::Live)
        .integer(&S::maxSteps, "max-steps", "Max steps", "sphere-tracing steps before a ray counts as a miss", 4, 1024,
                 U::Live)
        .real(&S::relaxation, "relaxation", "Relaxation", "over-relaxed steps of w x distance, undone when too long",
              1.0, 1.9, U::Live)
        .real(&S::hitThreshold, "hit-threshold", "Hit threshold",
              "|distance| below this many cells is a hit, for the pixels' and the probes' rays (the probes' path "
              "test keeps half a cell): lower sees through narrower openings, and through more thin walls",
              0.05, 2.0, U::Rebuild)
        .real(&S::offset, "offset", "Start offset", "rays start this many cells above the surface", 0.0, 8.0, U::Live)
        .real(&S::temporal, "temporal", "Temporal weight", "largest weight of the reprojected history while the camera moves (0 = none; a static view keeps averaging)", 0.0,
              0.99, U::Live)
        .integer(&S::filterRadius, "filter-radius", "Filter radius",
                 "edge-aware filter half-width in traced pixels; 0 = no blur, a joint bilateral upsample of the 2x2 "
                 "traced pixels around each pixel (SDFGI's probe light is smooth already)",
                 0, 4, U::Live)
        .real(&S::aoStrength, "ao", "Soft occlusion", "strength of the near-field occlusion written to \"ao\"", 0.0,
              1.0, U::Live)
        .real(&S::intensity, "intensity", "Intensity", "scales the indirect terms", 0.0, 16.0, U::Live)
        .choice(&S::sliceAxis, "slice-axis", "Slice axis", "axis sdf.slice cuts across", {"x", "y", "z"}, U::Live)
        .real(&S::slicePosition, "slice-position", "Slice position", "where along the axis, 0..1", 0.0, 1.0, U::Live)
        .integer(&S::sliceCascade, "slice-cascade", "Slice cascade", "which cascade sdf.slice shows (0 = the finest)", 0,
                 kMaxCascades - 1, U::Live);
        probes::addReflectionRows(t);
        return t;
    }();
    return table;
}

probes::FieldSettings SdfGiSettings::probeField() const {
    probes::FieldSettings f;
    f.rays = probeRays;
    f.rayBudget = rayBudget;
    f.pathTest = pathTest;
    f.hitThreshold = hitThreshold;
    return f;
}

}  // namespace gis
