// The probe field's parameter rows and the FieldSettings they make, declared once for every method
// that owns a field: the same keys, ranges and help under each method's name and the key prefix it
// chooses, so the methods cannot drift apart.
#pragma once

#include <string>

#include "param_table.h"
#include "probes/probe_field.h"
#include "probes/screen_reflection.h"

namespace gis::probes {

// The members of a method's settings S that hold the grid's rebuild parameters; `storage` may be
// null for a method that stores every probe one way.
template <class S>
struct GridMembers {
    float S::*spacing;
    int S::*rays;
    int S::*rayBudget;
    int S::*storage = nullptr;
};

// The rows that size the field (rebuild): PREFIXspacing, PREFIXrays, PREFIXray-budget and, when the
// method has one, PREFIXstorage. Every method keeps a grid per cascade of its volume
// (cascadeProbeGrids), so the spacing means the same under each.
template <class S>
void addGridRows(ParamTable<S>& t, const std::string& prefix, GridMembers<S> m) {
    using U = ParamUpdate;
    t.real(m.spacing, prefix + "spacing", "Probe spacing",
           "probe cell as a fraction of each cascade's extent (the coarsest: the scene's largest extent; >= 1: one "
           "probe per cascade)",
           0.02, 4.0, U::Rebuild);
    t.integer(m.rays, prefix + "rays", "Rays per probe", "rays each probe traces per update", 8, 512, U::Rebuild)
        .integer(m.rayBudget, prefix + "ray-budget", "Probe ray budget",
                 "probe rays per frame, spent on the due probes most urgent first (visible, least updated, most "
                 "changed); 0 = every due probe each frame",
                 0, 1 << 26, U::Rebuild);
    if (m.storage)
        t.choice(m.storage, prefix + "storage", "Storage",
                 "sh1 = SH L1 (64 B), sh2 = SH L2 (144 B), octahedral = 6x6 irradiance map (576 B); plus 1568 B "
                 "of distance moments and 32 B of state per probe",
                 {"sh1", "sh2", "octahedral"}, U::Rebuild);
}

// "METHOD.PREFIXkey": the full key of one of the rows above, for messages.
inline std::string gridKey(const std::string& method, const std::string& prefix, const std::string& key) {
    return method + "." + prefix + key;
}

// The help of every method's path-test row (a trade the method pages measure: issue #39).
inline const char* const kPathTestHelp =
    "with visibility, a probe counts only where its straight path to the shading point is clear through the "
    "method's volume: no light through walls thinner than the probe step, but a point no probe sees gets no "
    "probe light (HDDAGI lights it with rays of its own)";

// The rows a field reads live each frame: visibility, path test, feedback, hysteresis, convergence.
template <class S>
void addLiveFieldRows(ParamTable<S>& t) {
    using U = ParamUpdate;
    t.boolean(&S::visibility, "visibility", "Visibility", "Chebyshev visibility from the distance moments", U::Live)
        .boolean(&S::pathTest, "path-test", "Path test", kPathTestHelp, U::Live)
        .boolean(&S::bounces, "multibounce", "Multi-bounce", "probe rays' hits add the probes' own irradiance", U::Live)
        .real(&S::hysteresis, "hysteresis", "Hysteresis", "weight of the old value once a probe has warmed up", 0.0,
              0.99, U::Live)
        .real(&S::threshold, "threshold", "Convergence threshold",
              "largest relative change of an update below which the probes stop updating", 0.0, 1.0, U::Live)
        .integer(&S::maxUpdates, "max-updates", "Max updates", "updates per probe after which they stop anyway", 1,
                 100000, U::Live)
        .real(&S::normalBias, "normal-bias", "Normal/view bias", "offset of the shading point, x the probe step", 0.0,
              1.0, U::Live);
}

// What the field is built with and reads live, from a method's settings (its tracer, probe
// relocation and debug probe are the method's own).
template <class S>
FieldSettings fieldSettingsOf(const S& s) {
    FieldSettings f;
    f.storage = Storage(s.storage);
    f.rays = s.rays;
    f.rayBudget = s.rayBudget;
    f.visibility = s.visibility;
    f.pathTest = s.pathTest;
    f.bounces = s.bounces;
    f.hysteresis = s.hysteresis;
    f.threshold = s.threshold;
    f.maxUpdates = s.maxUpdates;
    f.normalBias = s.normalBias;
    return f;
}

// The screen reflection's rows (live): reflection, reflection-roughness, reflection-rays,
// reflection-frames, into the members S has from ReflectionSettings.
template <class S>
void addReflectionRows(ParamTable<S>& t) {
    using U = ParamUpdate;
    t.choice(&S::reflection, "reflection", "Reflection",
             "indirect.specular: rays = rays from the GGX lobe walked through the probes' volume and shaded as the "
             "probes' rays are; environment = the prefiltered sky alone (no rays, no occlusion: a mirror indoors "
             "shows the sky)",
             {"environment", "rays"}, U::Live)
        .real(&S::reflectionRoughness, "reflection-roughness", "Reflection roughness",
              "rays below this roughness, blended towards the diffuse gather over its last quarter; at and above "
              "it the specular term is the diffuse gather (the cosine lobe's mean radiance)",
              0.0, 1.0, U::Live)
        .integer(&S::reflectionRays, "reflection-rays", "Reflection rays",
                 "rays per pixel per frame from the GGX lobe (a mirror traces one)", 1, 64, U::Live)
        .integer(&S::reflectionFrames, "reflection-frames", "Reflection frames",
                 "frames of a still view averaged before it counts as settled", 1, 4096, U::Live);
}

}  // namespace gis::probes
