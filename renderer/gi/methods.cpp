// The registry of GI methods: an explicit list, not static self-registration (the renderer is a
// static library, and the linker would drop registrars nothing references). A new method adds its
// folders and ONE line below; tests may add more at run time with registerGiMethod().
#include "gi/method.h"

#define GIS_BUILTIN_METHODS(X) \
    X(noneMethod)              \
    X(ssaoMethod)              \
    X(aoReferenceMethod)       \
    X(pathtraceMethod)         \
    X(vctMethod)               \
    X(sdfMethod)               \
    X(probesMethod)            \
    X(hddagiMethod)            \
    X(lightmapMethod)

namespace gis {

#define GIS_DECLARE(fn) GiMethod fn();
GIS_BUILTIN_METHODS(GIS_DECLARE)
#undef GIS_DECLARE

std::vector<GiMethod>& methodRegistry() {
#define GIS_ENTRY(fn) fn(),
    static std::vector<GiMethod> methods{GIS_BUILTIN_METHODS(GIS_ENTRY)};
#undef GIS_ENTRY
    return methods;
}

// The shared parameter tables (ParamGroup): frame modules every method's frame uses.
ParamGroup emitterParamGroup();

const std::vector<ParamGroup>& paramGroups() {
    static const std::vector<ParamGroup> groups{emitterParamGroup()};
    return groups;
}

}  // namespace gis
