#include "gi/hddagi/hddagi_settings.h"

#include <string>

#include "probes/probe_params.h"
#include "volume/cascade_params.h"
#include "volume/volume_cascades.h"

namespace gis {

const ParamTable<HddagiSettings>& hddagiParams() {
    using S = HddagiSettings;
    using U = ParamUpdate;
    static const ParamTable<S> table = [] {
        ParamTable<S> t;
        t.integer(&S::resolution, "resolution", "Resolution", "voxels per edge of every cascade (a power of two)", 16,
                 256, U::Rebuild);
        addCascadeRows(t, "hddagi");
        probes::addGridRows(t, "", {&S::probeSpacing, &S::rays, &S::rayBudget, &S::storage});
        t.boolean(&S::halfResolution, "half-res", "Half resolution",
                 "gather the probes at every 2x2 block's first pixel and upsample (pixels on an edge gather their own)",
                 U::Rebuild);
        probes::addLiveFieldRows(t);
        probes::addReflectionRows(t);
        t.real(&S::intensity, "intensity", "Intensity", "scales indirect.diffuse", 0.0, 16.0, U::Live)
        .choice(&S::sliceAxis, "slice-axis", "Slice axis", "axis hddagi.occupancy cuts across", {"x", "y", "z"},
                U::Live)
        .real(&S::slicePosition, "slice-position", "Slice position", "where along the axis, 0..1", 0.0, 1.0, U::Live)
        .integer(&S::sliceCascade, "slice-cascade", "Slice cascade",
                 "which cascade hddagi.occupancy shows (0 = the finest)", 0, kMaxCascades - 1, U::Live)
        .choice(&S::sliceLevel, "slice-level", "Slice level",
                "what hddagi.occupancy shows: voxel bits, blocks with any bit, or region bits",
                {"voxels", "blocks", "regions"}, U::Live)
        .integer(&S::stepsMax, "steps-max", "Steps shown white", "traversal steps hddagi.steps shows as white", 1,
                 4096, U::Live);
        return t;
    }();
    return table;
}

probes::FieldSettings HddagiSettings::field() const {
    probes::FieldSettings f = probes::fieldSettingsOf(*this);
    f.tracer = probes::Tracer::Occupancy;
    return f;
}

probes::GatherSettings HddagiSettings::gather() const { return {normalBias, intensity, visibility, pathTest}; }

void checkHddagiSettings(const HddagiSettings& s) {
    probes::checkFieldSettings(s.field(), probes::gridKey("hddagi", "", "ray-budget"), probes::gridKey("hddagi", "", "rays"));
    const int r = s.resolution;
    if ((r & (r - 1)) != 0) throw Error("hddagi.resolution: " + std::to_string(r) + " must be a power of two in [16, 256]");
}

}  // namespace gis
