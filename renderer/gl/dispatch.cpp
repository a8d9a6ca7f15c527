#include "gl/dispatch.h"

#include <algorithm>
#include <string>

#include "error.h"

namespace gis::gl {

GLuint groupsFor(int64_t items, int local) {
    if (items <= 0) return 0;
    const int64_t groups = (items + local - 1) / local;
    if (groups > int64_t(UINT32_MAX)) throw Error("compute dispatch of " + std::to_string(items) + " items is too large");
    return GLuint(groups);
}

GLuint maxWorkGroupCount(int axis) {
    GLint v = 0;
    glGetIntegeri_v(GL_MAX_COMPUTE_WORK_GROUP_COUNT, GLuint(axis), &v);
    return v > 0 ? GLuint(v) : 65535u;  // the spec's minimum when the query fails
}

void dispatchCompute(GLuint x, GLuint y, GLuint z, const char* what) {
    const GLuint counts[3] = {x, y, z};
    for (int a = 0; a < 3; ++a)
        if (counts[a] > maxWorkGroupCount(a))
            throw Error(std::string(what) + ": " + std::to_string(counts[a]) + " work groups along axis " +
                        std::to_string(a) + " exceed this GPU's limit of " + std::to_string(maxWorkGroupCount(a)) +
                        " (GL_MAX_COMPUTE_WORK_GROUP_COUNT); use a smaller grid");
    if (x == 0 || y == 0 || z == 0) return;
    glDispatchCompute(x, y, z);
}

void dispatchComputeSplit(int64_t groups, const std::function<void(GLuint firstGroup)>& setFirstGroup) {
    const int64_t limit = maxWorkGroupCount(0);
    for (int64_t first = 0; first < groups; first += limit) {
        setFirstGroup(GLuint(first));
        glDispatchCompute(GLuint(std::min(limit, groups - first)), 1, 1);
    }
}

}  // namespace gis::gl
