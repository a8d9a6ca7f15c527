// The probe field's parameter rows and the FieldSettings they make, declared once for every method
// that owns a field and names its members as FieldSettings does (probes, hddagi): the same keys,
// ranges and help under each method's prefix, so the two cannot drift apart.
#pragma once

#include "gi/params.h"
#include "probes/probe_field.h"

namespace gis::probes {

// The rows a field reads live each frame: visibility, feedback, hysteresis, convergence.
template <class S>
void addLiveFieldRows(ParamTable<S>& t) {
    using U = ParamUpdate;
    t.boolean(&S::visibility, "visibility", "Visibility", "Chebyshev visibility from the distance moments", U::Live)
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
    f.bounces = s.bounces;
    f.hysteresis = s.hysteresis;
    f.threshold = s.threshold;
    f.maxUpdates = s.maxUpdates;
    f.normalBias = s.normalBias;
    return f;
}

}  // namespace gis::probes
