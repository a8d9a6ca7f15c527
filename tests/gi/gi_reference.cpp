#include "gi_reference.h"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>

#include "gi/method.h"

namespace gis::test {

const std::map<std::string, int> kCornellFaces = {
    {"floor", 0}, {"ceiling", 1}, {"back", 2}, {"red wall", 8}, {"green wall", 16}};

RenderSettings referenceSettings(const std::string& gi, const ReferenceSpec& spec) {
    RenderSettings r;
    r.width = r.height = spec.size;
    r.gi = gi;
    r.ambient = glm::vec3(0.0f);
    r.hdr32 = spec.hdr32;
    if (giMethod(gi).role == MethodRole::Reference)
        setParam(r, roleParamKey(MethodRole::Reference, "spp"), std::to_string(spec.spp));
    return r;
}

GiReference::GiReference(const std::string& builtin, const ReferenceSpec& spec)
    : builtin_(builtin), spec_(spec), scene_(makeBuiltinScene(builtin)) {
    hits_ = castPixels(scene_, 0, spec.size, spec.size, nullptr);
    interior_ = interiorPixels(hits_, spec.size, spec.size, 2, 0);
}

const ImageF& GiReference::render(const std::string& what, const RenderSettings& settings) const {
    std::unique_ptr<ImageF>& slot = images_[what];
    if (slot) return *slot;
    const char* dir = std::getenv("GIS_REF_CACHE");
    const std::string path = dir ? std::string(dir) + "/" + builtin_ + "_" + what + "_" + std::to_string(spec_.size) +
                                       "_" + std::to_string(spec_.spp) + (spec_.hdr32 ? "_f32" : "") + ".exr"
                                 : "";
    if (std::FILE* f = dir ? std::fopen(path.c_str(), "rb") : nullptr) {
        std::fclose(f);
        slot = std::make_unique<ImageF>(readExr(path));
        return *slot;
    }
    slot = std::make_unique<ImageF>(renderHdr(scene_, settings));
    if (dir) {  // written whole and renamed: a process reading it at once sees all of it or nothing
        std::filesystem::create_directories(dir);
        writeExr(path, *slot);
    }
    return *slot;
}

const ImageF& GiReference::direct() const { return render("direct", referenceSettings("none", spec_)); }

const ImageF& GiReference::pathTraced(int bounces) const {
    RenderSettings pt = referenceSettings(methodInRole(MethodRole::Reference).name, spec_);
    setParam(pt, roleParamKey(MethodRole::Reference, "bounces"), std::to_string(bounces));
    return render("pt" + std::to_string(bounces), pt);
}

ImageF GiReference::ptIndirect() const { return subtract(ptOneBounce(), ptDirect()); }

ImageF add(const ImageF& a, const ImageF& b) {
    ImageF r = a;
    for (size_t i = 0; i < r.rgba.size(); ++i)
        if (i % 4 != 3) r.rgba[i] += b.rgba[i];
    return r;
}

ImageF subtract(const ImageF& a, const ImageF& b) {
    ImageF r = a;
    for (size_t i = 0; i < r.rgba.size(); ++i)
        if (i % 4 != 3) r.rgba[i] -= b.rgba[i];
    return r;
}

GiReference::FloorBleeding GiReference::floorBleeding(const ImageF& indirect) const {
    const int w = indirect.width, h = indirect.height;
    double red[2] = {0, 0}, green[2] = {0, 0};
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const int i = y * w + x;
            if (!interior_[i] || hits_[i].region != kCornellFaces.at("floor")) continue;
            const int side = x < w / 4 ? 0 : x >= 3 * w / 4 ? 1 : -1;
            if (side < 0) continue;
            red[side] += indirect.at(x, y)[0];
            green[side] += indirect.at(x, y)[1];
        }
    return {red[0] / green[0], red[1] / green[1]};
}

double GiReference::regionMean(const ImageF& img, int region, int channel) const {
    return test::regionMean(img, hits_, interior_, region, channel);
}

const GiReference& giReference(const std::string& builtin, const ReferenceSpec& spec) {
    static std::map<std::string, std::unique_ptr<GiReference>> cache;
    const std::string key = builtin + "/" + std::to_string(spec.size) + "/" + std::to_string(spec.spp) + "/" +
                            std::to_string(spec.hdr32);
    std::unique_ptr<GiReference>& slot = cache[key];
    if (!slot) slot = std::make_unique<GiReference>(builtin, spec);
    return *slot;
}

bool measuring(const std::string& method) {
    const char* list = std::getenv("GIS_MEASURE");
    if (!list) return false;
    std::stringstream names(list);
    for (std::string name; std::getline(names, name, ',');)
        if (name == method || name == "all") return true;
    return false;
}

}  // namespace gis::test
