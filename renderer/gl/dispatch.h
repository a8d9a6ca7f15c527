// Compute dispatches checked against GL_MAX_COMPUTE_WORK_GROUP_COUNT. A count past the limit is
// GL_INVALID_VALUE: the dispatch does nothing and the pass reads whatever its buffers held (probes
// drew no indirect light at 41^3 probes). Every glDispatchCompute of the renderer goes through here.
#pragma once

#include <glad/gl.h>

#include <cstdint>
#include <functional>

namespace gis::gl {

// Work groups of `local` invocations covering `items` (ceil division).
GLuint groupsFor(int64_t items, int local);

// GL_MAX_COMPUTE_WORK_GROUP_COUNT of the current context, axis 0..2 (at least 65535 by the spec).
GLuint maxWorkGroupCount(int axis);

// One dispatch; throws gis::Error naming `what` and the limit when a count is past it (a grid
// too large for this GPU), instead of a dispatch that silently does nothing.
void dispatchCompute(GLuint x, GLuint y, GLuint z, const char* what);

// `groups` work groups along x (y = z = 1) in as many dispatches as the limit takes. Before each,
// `setFirstGroup(first)` is called with the index of its first group; the shader adds it to
// gl_WorkGroupID.x.
void dispatchComputeSplit(int64_t groups, const std::function<void(GLuint firstGroup)>& setFirstGroup);

}  // namespace gis::gl
