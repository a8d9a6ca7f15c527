// The scene volume's cascade rows, declared once for every method whose volume has cascades
// around the camera (sdf, hddagi, probes): the same keys, ranges and help under each method's name.
#pragma once

#include <string>

#include "param_table.h"
#include "volume/volume_cascades.h"

namespace gis {

// METHOD.cascades and METHOD.cascade-extent, into S::cascades and S::cascadeExtent (rebuild). The
// extent's help starts "world units": checks that scale a scene scale it too.
template <class S>
void addCascadeRows(ParamTable<S>& t, const std::string& method) {
    t.integer(&S::cascades, "cascades", "Cascades",
              "nested volumes around the camera, each twice the last; 0 = from the scene's extent and " + method +
                  ".cascade-extent",
              0, kMaxCascades, ParamUpdate::Rebuild)
        .real(&S::cascadeExtent, "cascade-extent", "Finest cascade extent",
              "world units: a scene cube up to this edge gets one volume; each doubling beyond it one more cascade; "
              "0 = from how near the render camera stands to what it sees (the same at every unit of length)",
              0.0, 1e9, ParamUpdate::Rebuild);
}

}  // namespace gis
