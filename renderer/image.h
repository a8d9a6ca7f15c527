// CPU images and their files: PNG (tonemapped sRGB, stb) and EXR (linear float, tinyexr).
// Files are written through scene/atomic_file.h: a complete new file or the old one, never a part.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace gis {

struct ImageF {  // RGBA float, rows top to bottom
    int width = 0, height = 0;
    std::vector<float> rgba;
    float* at(int x, int y) { return &rgba[(size_t(y) * width + x) * 4]; }
    const float* at(int x, int y) const { return &rgba[(size_t(y) * width + x) * 4]; }
};

struct ImageU8 {  // RGBA 8-bit, rows top to bottom
    int width = 0, height = 0;
    std::vector<uint8_t> rgba;
};

// GL stores the bottom row first; images here are top to bottom. Flips in place.
void flipVertically(ImageU8& image);
void flipVertically(ImageF& image);

// Each factor x factor block of pixels averaged into one (a box filter one output pixel wide: the
// Cycles references' pixel, the mean radiance over its square); a size not a multiple of factor
// loses its last rows and columns.
ImageF downsample(const ImageF& image, int factor);
ImageU8 downsample(const ImageU8& image, int factor);

// Throw gis::Error naming the file on failure; leave no partial file behind.
void writePng(const std::string& path, const ImageU8& image);
void writeExr(const std::string& path, const ImageF& image);  // RGB float32, ZIP
ImageF readExr(const std::string& path);
ImageU8 readPng(const std::string& path);

// The file's bytes, for a caller that writes several files as one set (writeFilesAtomically).
std::string encodePng(const ImageU8& image);
std::string encodeExr(const ImageF& image);

}  // namespace gis
