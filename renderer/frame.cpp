#include "frame.h"

#include <algorithm>

#include "error.h"

namespace gis {

void Frame::checkDeclared(const std::string& name, bool write) const {
    if (!pass) return;
    const std::vector<std::string> out = pass->outputs(), in = pass->inputs();
    if (std::find(out.begin(), out.end(), name) != out.end()) return;
    if (!write && std::find(in.begin(), in.end(), name) != in.end()) return;
    throw Error(std::string("internal: pass '") + pass->name() + (write ? "' writes '" : "' reads '") + name +
                "', which its " + (write ? "outputs()" : "inputs()") + " do not declare");
}

void Frame::put(const std::string& name, const gl::Texture& t) {
    checkDeclared(name, true);
    ResourceKind kind = ResourceKind::Texture2D;
    if (t.target == GL_TEXTURE_3D) kind = ResourceKind::Texture3D;
    else if (t.target == GL_TEXTURE_2D_ARRAY) kind = ResourceKind::Texture2DArray;
    else if (t.target == GL_TEXTURE_CUBE_MAP_ARRAY) kind = ResourceKind::TextureCubeArray;
    resources[name] = {t.id(), kind, t.format, t.width, t.height, t.depth, t.levels, 0};
}

void Frame::put(const std::string& name, const gl::Buffer& b) {
    checkDeclared(name, true);
    resources[name] = {b.id(), ResourceKind::Buffer, 0, 0, 0, 1, 1, b.size};
}

const FrameResource& Frame::resource(const std::string& name) const {
    checkDeclared(name, false);
    auto it = resources.find(name);
    if (it == resources.end()) throw Error("internal: no pass produced '" + name + "'");
    return it->second;
}

GLuint Frame::texture(const std::string& name) const {
    const FrameResource& r = resource(name);
    if (r.kind == ResourceKind::Buffer) throw Error("internal: '" + name + "' is a buffer, not a texture");
    return r.id;
}

GLuint Frame::buffer(const std::string& name) const {
    const FrameResource& r = resource(name);
    if (r.kind != ResourceKind::Buffer) throw Error("internal: '" + name + "' is a texture, not a buffer");
    return r.id;
}

StepTimers::Scope StepTimers::scope(const std::string& step) {
    for (auto& [name, timer] : steps)
        if (name == step) return Scope(timer.get());
    steps.emplace_back(step, std::make_unique<gl::GpuTimer>());
    return Scope(steps.back().second.get());
}

double median(std::vector<double> values) {
    if (values.empty()) return 0.0;
    std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
    return values[values.size() / 2];
}

double medianAfter(const std::vector<double>& values, int skip) {
    return median({values.begin() + std::min<size_t>(size_t(std::max(skip, 0)), values.size()), values.end()});
}

}  // namespace gis
