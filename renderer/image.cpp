#include "image.h"

#include <stb_image.h>
#include <stb_image_write.h>
#include <tinyexr.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "scene/atomic_file.h"
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

namespace {
template <class Image, class Sum>
Image boxDownsample(const Image& image, int factor, Sum sumOf) {
    Image out;
    out.width = image.width / factor;
    out.height = image.height / factor;
    out.rgba.resize(size_t(out.width) * out.height * 4);
    for (int y = 0; y < out.height; ++y)
        for (int x = 0; x < out.width; ++x)
            for (int c = 0; c < 4; ++c) {
                double sum = 0.0;
                for (int j = 0; j < factor; ++j)
                    for (int i = 0; i < factor; ++i)
                        sum += double(image.rgba[(size_t(y * factor + j) * image.width + size_t(x * factor + i)) * 4 + c]);
                out.rgba[(size_t(y) * out.width + x) * 4 + c] = sumOf(sum / double(factor * factor));
            }
    return out;
}
}  // namespace

ImageF downsample(const ImageF& image, int factor) {
    return boxDownsample(image, factor, [](double mean) { return float(mean); });
}

ImageU8 downsample(const ImageU8& image, int factor) {
    return boxDownsample(image, factor, [](double mean) { return uint8_t(std::lround(mean)); });
}

namespace {
void stbAppend(void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data), size_t(size));
}
}  // namespace

std::string encodePng(const ImageU8& image) {
    std::string bytes;
    if (!stbi_write_png_to_func(stbAppend, &bytes, image.width, image.height, 4, image.rgba.data(), image.width * 4))
        throw Error("cannot encode PNG");
    return bytes;
}

void writePng(const std::string& path, const ImageU8& image) {
    std::string bytes;
    try {
        bytes = encodePng(image);
    } catch (const Error& e) {
        throw Error(path + ": " + e.what());
    }
    writeFileAtomically(path, bytes);
}

std::string encodeExr(const ImageF& image) {
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
    // Encoded in memory and written by the atomic writer: tinyexr's own file writer ignores fclose's result.
    const char* err = nullptr;
    unsigned char* mem = nullptr;
    const size_t bytes = SaveEXRImageToMemory(&exr, &header, &mem, &err);
    if (bytes == 0 || !mem) {
        std::string msg = err ? err : "unknown error";
        if (err) FreeEXRErrorMessage(err);
        std::free(mem);
        throw Error("cannot encode EXR: " + msg);
    }
    std::string out(reinterpret_cast<const char*>(mem), bytes);
    std::free(mem);
    return out;
}

void writeExr(const std::string& path, const ImageF& image) {
    std::string bytes;
    try {
        bytes = encodeExr(image);
    } catch (const Error& e) {
        throw Error(path + ": " + e.what());
    }
    writeFileAtomically(path, bytes);
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
