#include "gi/probes/probe_settings.h"

#include <string>

#include "probes/probe_params.h"
#include "volume/cascade_params.h"

namespace gis {

const ParamTable<ProbeSettings>& probeParams() {
    using S = ProbeSettings;
    using U = ParamUpdate;
    static const ParamTable<S> table = [] {
        ParamTable<S> t;
        probes::addGridRows(t, "", {&S::spacing, &S::rays, &S::rayBudget, &S::storage});
        t.integer(&S::sdfResolution, "sdf-resolution", "SDF resolution",
                 "voxels and distance-field cells per edge of each cascade (a power of two)", 8, 256, U::Rebuild);
        addCascadeRows(t, "probes");
        t.choice(&S::inside, "inside", "Probes inside geometry",
                "relocate = pushed out along the distance field's gradient (at most 0.45 of a probe step), else off; off = "
                "switched off",
                {"relocate", "off"}, U::Rebuild);
        probes::addLiveFieldRows(t);
        probes::addReflectionRows(t);
        t.choice(&S::gatherScale, "gather-scale", "Gather scale",
                "1 = gather every pixel; 2, 4 = every 2x2 / 4x4 block's first pixel, spread by joint bilateral "
                "upsampling (pixels on an edge gather their own)",
                {"1", "2", "4"}, U::Rebuild)
        .real(&S::intensity, "intensity", "Intensity", "scales indirect.diffuse", 0.0, 16.0, U::Live)
        .integer(&S::debugProbe, "debug-probe", "Debug probe",
                 "the probe whose last rays probes.rays draws (x fastest, then y, z); -1 = the middle one", -1,
                 (1 << 18) - 1, U::Live);
        return t;
    }();
    return table;
}

probes::FieldSettings ProbeSettings::field() const {
    probes::FieldSettings f = probes::fieldSettingsOf(*this);
    f.relocate = inside == 0;
    f.debugProbe = debugProbe;
    return f;
}

void checkProbeSettings(const ProbeSettings& s) {
    probes::checkFieldSettings(s.field(), probes::gridKey("probes", "", "ray-budget"), probes::gridKey("probes", "", "rays"));
    const int r = s.sdfResolution;
    if (r < 8 || r > 256 || (r & (r - 1)) != 0)
        throw Error("probes.sdf-resolution: " + std::to_string(r) + " must be a power of two in [8, 256]");
}

}  // namespace gis
