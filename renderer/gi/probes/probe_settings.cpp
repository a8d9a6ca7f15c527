#include "gi/probes/probe_settings.h"

#include <string>

#include "probes/probe_params.h"

namespace gis {

const ParamTable<ProbeSettings>& probeParams() {
    using S = ProbeSettings;
    using U = ParamUpdate;
    static const ParamTable<S> table = [] {
        ParamTable<S> t;
        t.real(&S::spacing, "spacing", "Probe spacing",
              "cell width as a fraction of the scene's largest extent (>= 1: one probe)", 0.02, 4.0, U::Rebuild)
        .integer(&S::rays, "rays", "Rays per probe", "rays each probe traces per update", 8, 512, U::Rebuild)
        .choice(&S::storage, "storage", "Storage",
                "sh1 = SH L1 (64 B), sh2 = SH L2 (144 B), octahedral = 6x6 irradiance map (576 B); plus 1568 B "
                "of distance moments and 32 B of state per probe",
                {"sh1", "sh2", "octahedral"}, U::Rebuild)
        .integer(&S::rayBudget, "ray-budget", "Ray budget",
                 "probe rays per frame, spent on the due probes most urgent first (visible, least updated, most "
                 "changed); 0 = every due probe each frame",
                 0, 1 << 26, U::Rebuild)
        .integer(&S::sdfResolution, "sdf-resolution", "SDF resolution",
                 "voxels and distance-field cells per edge (a power of two)", 8, 256, U::Rebuild)
        .choice(&S::inside, "inside", "Probes inside geometry",
                "relocate = pushed out along the distance field's gradient (at most 0.45 of a probe step), else off; off = "
                "switched off",
                {"relocate", "off"}, U::Rebuild);
        probes::addLiveFieldRows(t);
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
    probes::checkFieldSettings(s.field(), "probes.ray-budget", "probes.rays");
    const int r = s.sdfResolution;
    if (r < 8 || r > 256 || (r & (r - 1)) != 0)
        throw Error("probes.sdf-resolution: " + std::to_string(r) + " must be a power of two in [8, 256]");
}

}  // namespace gis
