#include "view_test_util.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <memory>

#include "gl/gl.h"

namespace gis::test {

GlContext& viewContext() {
    static std::unique_ptr<GlContext> ctx = [] {
        ContextOptions o;
        o.backend = Backend::Auto;
        return createContext(o);
    }();
    return *ctx;
}

GlObjectCounts countGlObjects() {
    // A deleted program stays alive while it is the current one: unbind it first.
    glUseProgram(0);
    glBindVertexArray(0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    // The next name of each kind is one past the highest handed out: create one, note it, delete it.
    GLuint probe[7] = {};
    glCreateTextures(GL_TEXTURE_2D, 1, &probe[0]);
    glCreateBuffers(1, &probe[1]);
    glCreateFramebuffers(1, &probe[2]);
    glCreateVertexArrays(1, &probe[3]);
    glCreateSamplers(1, &probe[4]);
    glCreateQueries(GL_TIMESTAMP, 1, &probe[5]);
    probe[6] = glCreateProgram();
    GlObjectCounts c;
    auto count = [](GLuint limit, GLboolean (*is)(GLuint)) {
        int n = 0;
        for (GLuint name = 1; name < limit; ++name) n += is(name) == GL_TRUE;
        return n;
    };
    c.textures = count(probe[0], [](GLuint n) { return glIsTexture(n); });
    c.buffers = count(probe[1], [](GLuint n) { return glIsBuffer(n); });
    c.framebuffers = count(probe[2], [](GLuint n) { return glIsFramebuffer(n); });
    c.vertexArrays = count(probe[3], [](GLuint n) { return glIsVertexArray(n); });
    c.samplers = count(probe[4], [](GLuint n) { return glIsSampler(n); });
    c.queries = count(probe[5], [](GLuint n) { return glIsQuery(n); });
    // A program we deleted while GL still uses it (Mesa keeps one such reference around) is flagged
    // for deletion and freed by GL later: not ours any more.
    c.programs = count(probe[6], [](GLuint n) -> GLboolean {
        if (!glIsProgram(n)) return GL_FALSE;
        GLint deleted = 0;
        glGetProgramiv(n, GL_DELETE_STATUS, &deleted);
        return deleted ? GL_FALSE : GL_TRUE;
    });
    glDeleteTextures(1, &probe[0]);
    glDeleteBuffers(1, &probe[1]);
    glDeleteFramebuffers(1, &probe[2]);
    glDeleteVertexArrays(1, &probe[3]);
    glDeleteSamplers(1, &probe[4]);
    glDeleteQueries(1, &probe[5]);
    glDeleteProgram(probe[6]);
    return c;
}

std::string describe(const GlObjectCounts& c) {
    return std::to_string(c.textures) + " textures, " + std::to_string(c.buffers) + " buffers, " +
           std::to_string(c.framebuffers) + " framebuffers, " + std::to_string(c.vertexArrays) + " vertex arrays, " +
           std::to_string(c.samplers) + " samplers, " + std::to_string(c.queries) + " queries, " +
           std::to_string(c.programs) + " programs";
}

double meanAbsDiff(const ImageU8& a, const ImageU8& b) {
    EXPECT_EQ(a.width, b.width);
    EXPECT_EQ(a.height, b.height);
    if (a.rgba.size() != b.rgba.size() || a.rgba.empty()) return 1e9;
    double sum = 0.0;
    for (size_t i = 0; i < a.rgba.size(); i += 4)
        for (int k = 0; k < 3; ++k) sum += std::abs(int(a.rgba[i + k]) - int(b.rgba[i + k]));
    return sum / double(a.rgba.size() / 4 * 3);
}

}  // namespace gis::test
