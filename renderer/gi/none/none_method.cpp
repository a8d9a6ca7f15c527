// `--gi none`: direct light with shadow maps and the constant ambient term: the baseline every
// method's indirect light is measured against. It adds no pass; its cost and accuracy knob is
// shadow-map resolution, which its presets set.
#include "gi/method.h"

namespace gis {

GiMethod noneMethod() {
    GiMethod m;
    m.name = "none";
    m.summary = "direct light with shadow maps plus the constant ambient term (the baseline)";
    const int maps[3] = {256, 1024, 2048}, cubes[3] = {128, 512, 1024};
    for (int i = 0; i < 3; ++i)
        m.presets.push_back({presetNames()[i],
                             "shadow maps " + std::to_string(maps[i]) + ", cubes " + std::to_string(cubes[i]),
                             {}, maps[i], cubes[i]});
    m.addPasses = [](MethodBuild&) {};
    return m;
}

}  // namespace gis
