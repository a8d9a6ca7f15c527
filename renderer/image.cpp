#include "image.h"

#include <stb_image.h>
#include <stb_image_write.h>
#include <tinyexr.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "scene/scene.h"

namespace gis {

namespace {
template <typename T>
void flipRows(std::vector<T>& data, int width, int height) {
    const size_t row = size_t(width) * 4;
    for (int y = 0; y < height / 2; ++y)
        std::swap_ranges(data.begin() + y * row, data.begin() + (y + 1) * row, data.begin() + (height - 1 - y) * row);
}
}  // namespace

void flipVertically(ImageU8& image) { flipRows(image.rgba, image.width, image.height); }
void flipVertically(ImageF& image) { flipRows(image.rgba, image.width, image.height); }

void writeAtomically(const std::string& path, const std::function<void(const std::string&)>& write) {
    namespace fs = std::filesystem;
    fs::path target(path);
    if (target.has_parent_path() && !fs::is_directory(target.parent_path()))
        throw Error(path + ": directory " + target.parent_path().string() + " does not exist");
    const std::string tmp = path + ".tmp" + std::to_string(::getpid());
    try {
        write(tmp);
        std::error_code ec;
        fs::rename(tmp, target, ec);
        if (ec) throw Error(path + ": cannot rename temporary file: " + ec.message());
    } catch (...) {
        std::error_code ignored;
        fs::remove(tmp, ignored);
        throw;
    }
}

void writePng(const std::string& path, const ImageU8& image) {
    writeAtomically(path, [&](const std::string& tmp) {
        if (!stbi_write_png(tmp.c_str(), image.width, image.height, 4, image.rgba.data(), image.width * 4))
            throw Error(path + ": cannot write PNG");
    });
}

void writeExr(const std::string& path, const ImageF& image) {
    writeAtomically(path, [&](const std::string& tmp) {
        EXRHeader header;
        InitEXRHeader(&header);
        EXRImage exr;
        InitEXRImage(&exr);
        const size_t n = size_t(image.width) * image.height;
        std::vector<float> planes[3];
        for (int c = 0; c < 3; ++c) {
            planes[c].resize(n);
            for (size_t i = 0; i < n; ++i) planes[c][i] = image.rgba[i * 4 + c];
        }
        // EXR stores channels in alphabetical order: B, G, R.
        float* ptrs[3] = {planes[2].data(), planes[1].data(), planes[0].data()};
        exr.images = reinterpret_cast<unsigned char**>(ptrs);
        exr.num_channels = 3;
        exr.width = image.width;
        exr.height = image.height;
        EXRChannelInfo channels[3] = {};
        const char* names[3] = {"B", "G", "R"};
        int pixelTypes[3], requested[3];
        for (int c = 0; c < 3; ++c) {
            std::snprintf(channels[c].name, sizeof channels[c].name, "%s", names[c]);
            pixelTypes[c] = TINYEXR_PIXELTYPE_FLOAT;
            requested[c] = TINYEXR_PIXELTYPE_FLOAT;
        }
        header.num_channels = 3;
        header.channels = channels;
        header.pixel_types = pixelTypes;
        header.requested_pixel_types = requested;
        header.compression_type = TINYEXR_COMPRESSIONTYPE_ZIP;
        const char* err = nullptr;
        if (SaveEXRImageToFile(&exr, &header, tmp.c_str(), &err) != TINYEXR_SUCCESS) {
            std::string msg = err ? err : "unknown error";
            if (err) FreeEXRErrorMessage(err);
            throw Error(path + ": cannot write EXR: " + msg);
        }
    });
}

ImageF readExr(const std::string& path) {
    float* data = nullptr;
    int w = 0, h = 0;
    const char* err = nullptr;
    if (LoadEXR(&data, &w, &h, path.c_str(), &err) != TINYEXR_SUCCESS) {
        std::string msg = err ? err : "unknown error";
        if (err) FreeEXRErrorMessage(err);
        throw Error(path + ": cannot read EXR: " + msg);
    }
    ImageF img;
    img.width = w;
    img.height = h;
    img.rgba.assign(data, data + size_t(w) * h * 4);
    std::free(data);
    return img;
}

ImageU8 readPng(const std::string& path) {
    int w = 0, h = 0, n = 0;
    unsigned char* data = stbi_load(path.c_str(), &w, &h, &n, 4);
    if (!data) throw Error(path + ": cannot read image: " + stbi_failure_reason());
    ImageU8 img;
    img.width = w;
    img.height = h;
    img.rgba.assign(data, data + size_t(w) * h * 4);
    stbi_image_free(data);
    return img;
}

}  // namespace gis
