#include "metrics.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>

#include "error.h"

namespace gis {

namespace {

constexpr double kPi = 3.14159265358979323846;

using Plane = std::vector<double>;  // one channel, width*height, rows top to bottom

std::string sizeText(const ImageF& img) { return std::to_string(img.width) + "x" + std::to_string(img.height); }

void checkImage(const ImageF& img, const char* what) {
    if (img.width <= 0 || img.height <= 0) throw Error(std::string(what) + " is empty (" + sizeText(img) + ")");
    const size_t expected = size_t(img.width) * size_t(img.height) * 4;
    if (img.rgba.size() != expected)
        throw Error(std::string(what) + " holds " + std::to_string(img.rgba.size()) + " floats, not the " +
                    std::to_string(expected) + " of " + sizeText(img) + " RGBA pixels");
    static const char* channelNames[3] = {"R", "G", "B"};
    for (size_t i = 0; i < expected; i += 4)
        for (int c = 0; c < 3; ++c) {
            const float v = img.rgba[i + c];
            if (!std::isfinite(v)) {
                const size_t p = i / 4;
                throw Error(std::string(what) + " has " + (std::isnan(v) ? "NaN" : "Inf") + " at pixel (" +
                            std::to_string(p % size_t(img.width)) + ", " + std::to_string(p / size_t(img.width)) +
                            "), channel " + channelNames[c]);
            }
        }
}

bool ignored(const std::vector<uint8_t>& ignore, size_t p) { return !ignore.empty() && ignore[p] != 0; }

// Mean of a per-pixel quantity over the pixels not ignored (validateImagePair guarantees one).
template <typename F>
double meanOverPixels(size_t count, const std::vector<uint8_t>& ignore, F&& value) {
    double sum = 0.0;
    size_t n = 0;
    for (size_t p = 0; p < count; ++p) {
        if (ignored(ignore, p)) continue;
        sum += value(p);
        ++n;
    }
    return n ? sum / double(n) : 0.0;
}

double meanOfMap(const ErrorMap& map, const std::vector<uint8_t>& ignore) {
    return meanOverPixels(map.values.size(), ignore, [&](size_t p) { return double(map.values[p]); });
}

Plane channelPlane(const ImageF& img, int c, bool clamp01 = false) {
    Plane out(size_t(img.width) * img.height);
    for (size_t p = 0; p < out.size(); ++p) {
        const double v = img.rgba[p * 4 + c];
        out[p] = clamp01 ? std::clamp(v, 0.0, 1.0) : v;
    }
    return out;
}

// --- Separable convolution ------------------------------------------------------------------
// `kernel` has 2r+1 taps, centred. Two border rules: clamp to edge (FLIP, as in its paper's code),
// or drop the taps outside the image and renormalise the rest (SSIM).
enum class Border { Clamp, Renormalize };

Plane convolve1D(const Plane& src, int w, int h, const std::vector<double>& kernel, bool horizontal, Border border) {
    const int r = int(kernel.size() / 2);
    Plane dst(src.size());
    const int n = horizontal ? w : h;        // length along the filter direction
    const int lines = horizontal ? h : w;
    const size_t step = horizontal ? 1 : size_t(w);
    for (int line = 0; line < lines; ++line) {
        const size_t base = horizontal ? size_t(line) * w : size_t(line);
        for (int i = 0; i < n; ++i) {
            double sum = 0.0, weight = 0.0;
            for (int k = -r; k <= r; ++k) {
                int j = i + k;
                if (j < 0 || j >= n) {
                    if (border == Border::Renormalize) continue;
                    j = std::clamp(j, 0, n - 1);
                }
                const double wk = kernel[size_t(k + r)];
                sum += wk * src[base + size_t(j) * step];
                weight += wk;
            }
            dst[base + size_t(i) * step] = border == Border::Renormalize ? sum / weight : sum;
        }
    }
    return dst;
}

Plane convolve(const Plane& src, int w, int h, const std::vector<double>& kx, const std::vector<double>& ky,
               Border border) {
    return convolve1D(convolve1D(src, w, h, kx, true, border), w, h, ky, false, border);
}

// --- SSIM -------------------------------------------------------------------------------------
// Wang, Bovik, Sheikh, Simoncelli 2004: SSIM = (2 mx my + C1)(2 sxy + C2) / ((mx^2 + my^2 + C1)(sx^2 + sy^2 + C2))
// with local Gaussian-weighted means, variances and covariance; C1 = (K1 L)^2, C2 = (K2 L)^2.
constexpr int kSsimRadius = 5;       // 11x11 window
constexpr double kSsimSigma = 1.5;
constexpr double kSsimK1 = 0.01, kSsimK2 = 0.03, kSsimRange = 1.0;

ErrorMap ssimMapUnchecked(const ImageF& test, const ImageF& reference) {
    const int w = test.width, h = test.height;
    std::vector<double> g;
    for (int k = -kSsimRadius; k <= kSsimRadius; ++k) g.push_back(std::exp(-double(k * k) / (2 * kSsimSigma * kSsimSigma)));
    const double c1 = (kSsimK1 * kSsimRange) * (kSsimK1 * kSsimRange);
    const double c2 = (kSsimK2 * kSsimRange) * (kSsimK2 * kSsimRange);
    ErrorMap map{w, h, std::vector<float>(size_t(w) * h, 0.0f)};
    for (int c = 0; c < 3; ++c) {
        const Plane x = channelPlane(test, c), y = channelPlane(reference, c);
        Plane xx(x.size()), yy(x.size()), xy(x.size());
        for (size_t p = 0; p < x.size(); ++p) {
            xx[p] = x[p] * x[p];
            yy[p] = y[p] * y[p];
            xy[p] = x[p] * y[p];
        }
        auto blur = [&](const Plane& in) { return convolve(in, w, h, g, g, Border::Renormalize); };
        const Plane mx = blur(x), my = blur(y), mxx = blur(xx), myy = blur(yy), mxy = blur(xy);
        for (size_t p = 0; p < x.size(); ++p) {
            const double vx = mxx[p] - mx[p] * mx[p];
            const double vy = myy[p] - my[p] * my[p];
            const double cxy = mxy[p] - mx[p] * my[p];
            const double s = ((2 * mx[p] * my[p] + c1) * (2 * cxy + c2)) /
                             ((mx[p] * mx[p] + my[p] * my[p] + c1) * (vx + vy + c2));
            map.values[p] += float(s / 3.0);
        }
    }
    return map;
}

// --- FLIP -------------------------------------------------------------------------------------
// LDR-FLIP after Andersson, Nilsson, Akenine-Moeller, Oskarsson, Astrom, Fairchild:
// "FLIP: A Difference Evaluator for Alternating Images", HPG 2020. Our implementation of the
// paper's pipeline, per pixel:
//  colour: linear RGB -> YyCxCz (the linearised CIELAB opponent space); each channel filtered
//          with the spatial contrast sensitivity of that channel, a sum of Gaussians in visual
//          degrees  a1 sqrt(pi/b1) exp(-pi^2 x^2/b1) + a2 sqrt(pi/b2) exp(-pi^2 x^2/b2),
//          sampled at 1/ppd, radius ceil(3 sqrt(b_max/(2 pi^2)) ppd) for all three, normalised
//          to sum 1 (achromatic a1 1, b1 0.0047; red-green a1 1, b1 0.0053; blue-yellow
//          a1 34.1, b1 0.04, a2 13.5, b2 0.025); back to linear RGB, clamped to [0, 1]; CIELAB;
//          Hunt adjustment a*, b* scaled by 0.01 L*; HyAB distance |dL| + |(da, db)|;
//          raised to qc = 0.7 and mapped to [0, 1] piecewise linearly: [0, pc cmax] -> [0, pt],
//          [pc cmax, cmax] -> [pt, 1] with pc 0.4, pt 0.95, cmax = HyAB(green, blue)^qc.
//  features: on the unfiltered luminance Y/Yn, first (edges) and second (points) derivatives of
//          a Gaussian of sigma 0.5 * 0.082 deg * ppd pixels, radius ceil(3 sigma), positive
//          weights normalised to 1 and negative ones to -1, along x and along y; feature error
//          = (max(| |e_ref| - |e_test| |, | |p_ref| - |p_test| |) / sqrt 2)^qf, qf = 0.5.
//  combined: FLIP = colour error ^ (1 - feature error).
// Borders are clamped to the edge pixel. Deviations: the filters run as separable 1D passes
// (the same kernels: each Gaussian is a product of 1D ones), in double precision; inputs are
// display-referred linear RGB (our tone mapper's output) rather than decoded sRGB 8-bit files;
// HDR-FLIP's exposure bracketing is not implemented.
constexpr double kFlipQc = 0.7, kFlipQf = 0.5, kFlipPc = 0.4, kFlipPt = 0.95;
constexpr double kFlipFeatureWidthDeg = 0.082;

struct CsfChannel { double a1, b1, a2, b2; };
constexpr CsfChannel kCsf[3] = {{1.0, 0.0047, 0.0, 0.0}, {1.0, 0.0053, 0.0, 0.0}, {34.1, 0.04, 13.5, 0.025}};
constexpr double kCsfMaxB = 0.04;

// Linear sRGB primaries, D65 (IEC 61966-2-1), to CIE XYZ. glm matrices are column-major:
// each group of three is one column (the XYZ of R, G, B).
const glm::dmat3& rgbToXyz() {
    static const glm::dmat3 m(0.4124564, 0.2126729, 0.0193339,
                              0.3575761, 0.7151522, 0.1191920,
                              0.1804375, 0.0721750, 0.9503041);
    return m;
}
const glm::dmat3& xyzToRgb() {
    static const glm::dmat3 m = glm::inverse(rgbToXyz());
    return m;
}
const glm::dvec3& whiteXyz() {  // reference white: linear RGB (1, 1, 1)
    static const glm::dvec3 w = rgbToXyz() * glm::dvec3(1.0);
    return w;
}

glm::dvec3 rgbToYcxcz(glm::dvec3 rgb) {
    const glm::dvec3 n = rgbToXyz() * rgb / whiteXyz();
    return {116.0 * n.y - 16.0, 500.0 * (n.x - n.y), 200.0 * (n.y - n.z)};
}

glm::dvec3 ycxczToRgb(glm::dvec3 c) {
    const double y = (c.x + 16.0) / 116.0;
    const glm::dvec3 n(c.y / 500.0 + y, y, y - c.z / 200.0);
    return xyzToRgb() * (n * whiteXyz());
}

double labF(double t) {
    constexpr double d = 6.0 / 29.0;
    return t > d * d * d ? std::cbrt(t) : t / (3.0 * d * d) + 4.0 / 29.0;
}

glm::dvec3 huntAdjust(glm::dvec3 lab) { return {lab.x, 0.01 * lab.x * lab.y, 0.01 * lab.x * lab.z}; }

double hyab(glm::dvec3 a, glm::dvec3 b) {
    const glm::dvec3 d = a - b;
    return std::abs(d.x) + std::sqrt(d.y * d.y + d.z * d.z);
}

double flipCmax() {
    static const double cmax = std::pow(
        hyab(huntAdjust(flipdetail::linearRgbToLab({0, 1, 0})), huntAdjust(flipdetail::linearRgbToLab({0, 0, 1}))),
        kFlipQc);
    return cmax;
}

// The CSF of one channel as a sum of separable Gaussians: weight_i * (g_i along x) (g_i along y).
struct SeparableSum {
    std::vector<std::vector<double>> kernels;
    std::vector<double> weights;
};

SeparableSum csfFilter(const CsfChannel& ch, double ppd) {
    const int r = int(std::ceil(3.0 * std::sqrt(kCsfMaxB / (2.0 * kPi * kPi)) * ppd));
    const double dx = 1.0 / ppd;
    SeparableSum f;
    double total = 0.0;
    const double as[2] = {ch.a1, ch.a2}, bs[2] = {ch.b1, ch.b2};
    for (int i = 0; i < 2; ++i) {
        if (as[i] == 0.0) continue;
        std::vector<double> g;
        double sum = 0.0;
        for (int k = -r; k <= r; ++k) {
            const double x = k * dx;
            g.push_back(std::exp(-kPi * kPi * x * x / bs[i]));
            sum += g.back();
        }
        const double amplitude = as[i] * std::sqrt(kPi / bs[i]);
        f.kernels.push_back(g);
        f.weights.push_back(amplitude);
        total += amplitude * sum * sum;  // sum of the 2D kernel
    }
    for (double& wgt : f.weights) wgt /= total;
    return f;
}

struct FeatureKernels {
    std::vector<double> gauss, edge, point;
};

FeatureKernels featureKernels(double ppd) {
    const double sd = 0.5 * kFlipFeatureWidthDeg * ppd;
    const int r = int(std::ceil(3.0 * sd));
    FeatureKernels k;
    double gSum = 0.0, edgePos = 0.0, pointPos = 0.0, pointNeg = 0.0;
    for (int x = -r; x <= r; ++x) {
        const double g = std::exp(-double(x * x) / (2.0 * sd * sd));
        const double e = -double(x) * g;
        const double p = (double(x * x) / (sd * sd) - 1.0) * g;
        k.gauss.push_back(g);
        k.edge.push_back(e);
        k.point.push_back(p);
        gSum += g;
        if (e > 0) edgePos += e;
        (p > 0 ? pointPos : pointNeg) += std::abs(p);
    }
    // The 2D filters are (derivative along one axis) x (Gaussian along the other). Normalising the
    // Gaussian factor to sum 1 and the derivative factor's positive and negative lobes to +1 and -1
    // normalises the 2D filter's lobes the same way. The edge filter is odd: both lobes weigh edgePos.
    for (double& g : k.gauss) g /= gSum;
    for (double& e : k.edge) e /= edgePos;
    for (double& p : k.point) p /= p > 0 ? pointPos : pointNeg;
    return k;
}

struct FlipPrepared {
    std::vector<glm::dvec3> lab;  // Hunt-adjusted L*a*b* after the CSF filters
    Plane edge, point;            // feature magnitudes
};

FlipPrepared prepareFlip(const ImageF& img, double ppd) {
    const int w = img.width, h = img.height;
    const size_t n = size_t(w) * h;
    Plane opp[3];
    for (auto& p : opp) p.resize(n);
    Plane luminance(n);
    for (size_t p = 0; p < n; ++p) {
        glm::dvec3 rgb(img.rgba[p * 4], img.rgba[p * 4 + 1], img.rgba[p * 4 + 2]);
        rgb = glm::clamp(rgb, 0.0, 1.0);
        const glm::dvec3 c = rgbToYcxcz(rgb);
        for (int k = 0; k < 3; ++k) opp[k][p] = c[k];
        luminance[p] = (c.x + 16.0) / 116.0;  // Y / Yn
    }
    Plane filtered[3];
    for (int k = 0; k < 3; ++k) {
        const SeparableSum f = csfFilter(kCsf[k], ppd);
        filtered[k].assign(n, 0.0);
        for (size_t i = 0; i < f.kernels.size(); ++i) {
            const Plane part = convolve(opp[k], w, h, f.kernels[i], f.kernels[i], Border::Clamp);
            for (size_t p = 0; p < n; ++p) filtered[k][p] += f.weights[i] * part[p];
        }
    }
    FlipPrepared out;
    out.lab.resize(n);
    for (size_t p = 0; p < n; ++p) {
        const glm::dvec3 rgb = glm::clamp(ycxczToRgb({filtered[0][p], filtered[1][p], filtered[2][p]}), 0.0, 1.0);
        out.lab[p] = huntAdjust(flipdetail::linearRgbToLab(rgb));
    }
    const FeatureKernels fk = featureKernels(ppd);
    const Plane ex = convolve(luminance, w, h, fk.edge, fk.gauss, Border::Clamp);
    const Plane ey = convolve(luminance, w, h, fk.gauss, fk.edge, Border::Clamp);
    const Plane px = convolve(luminance, w, h, fk.point, fk.gauss, Border::Clamp);
    const Plane py = convolve(luminance, w, h, fk.gauss, fk.point, Border::Clamp);
    out.edge.resize(n);
    out.point.resize(n);
    for (size_t p = 0; p < n; ++p) {
        out.edge[p] = std::hypot(ex[p], ey[p]);
        out.point[p] = std::hypot(px[p], py[p]);
    }
    return out;
}

ErrorMap flipMapUnchecked(const ImageF& test, const ImageF& reference, double ppd) {
    if (!(ppd > 0.0) || !std::isfinite(ppd) || ppd > 1e4)
        throw Error("FLIP pixels per degree must be in (0, 10000], not " + formatMetric(ppd));
    const FlipPrepared t = prepareFlip(test, ppd), r = prepareFlip(reference, ppd);
    ErrorMap map{test.width, test.height, std::vector<float>(t.lab.size())};
    for (size_t p = 0; p < t.lab.size(); ++p) {
        const double colour = flipdetail::colorErrorFromHyab(hyab(r.lab[p], t.lab[p]));
        const double feature = std::max(std::abs(r.edge[p] - t.edge[p]), std::abs(r.point[p] - t.point[p]));
        const double featureError = std::min(1.0, std::pow(feature / std::sqrt(2.0), kFlipQf));
        map.values[p] = float(std::pow(colour, 1.0 - featureError));
    }
    return map;
}

// --- Per-pixel linear-radiance maps ----------------------------------------------------------------
ErrorMap pixelMap(const ImageF& test, const ImageF& reference, bool relative, double epsilon) {
    ErrorMap map{test.width, test.height, std::vector<float>(size_t(test.width) * test.height)};
    for (size_t p = 0; p < map.values.size(); ++p) {
        double sum = 0.0;
        for (int c = 0; c < 3; ++c) {
            const double t = test.rgba[p * 4 + c], r = reference.rgba[p * 4 + c];
            sum += relative ? (t - r) * (t - r) / (r * r + epsilon) : (t - r) * (t - r);
        }
        map.values[p] = float(relative ? sum / 3.0 : std::sqrt(sum / 3.0));
    }
    return map;
}

double mseUnchecked(const ImageF& test, const ImageF& reference, const std::vector<uint8_t>& ignore) {
    return meanOverPixels(size_t(test.width) * test.height, ignore, [&](size_t p) {
        double sum = 0.0;
        for (int c = 0; c < 3; ++c) {
            const double d = double(test.rgba[p * 4 + c]) - double(reference.rgba[p * 4 + c]);
            sum += d * d;
        }
        return sum / 3.0;
    });
}

double relMseUnchecked(const ImageF& test, const ImageF& reference, double epsilon,
                       const std::vector<uint8_t>& ignore) {
    if (!(epsilon > 0.0) || !std::isfinite(epsilon))
        throw Error("relative MSE epsilon must be a positive number, not " + formatMetric(epsilon));
    return meanOverPixels(size_t(test.width) * test.height, ignore, [&](size_t p) {
        double sum = 0.0;
        for (int c = 0; c < 3; ++c) {
            const double r = reference.rgba[p * 4 + c];
            const double d = double(test.rgba[p * 4 + c]) - r;
            sum += d * d / (r * r + epsilon);
        }
        return sum / 3.0;
    });
}

void checkPeak(double peak) {
    if (!(peak > 0.0) || !std::isfinite(peak)) throw Error("PSNR peak must be a positive number, not " + formatMetric(peak));
}

// --- Heatmap colours ------------------------------------------------------------------------------
// Our own ramp, defined in CIELAB: lightness L* rises linearly from 4 to 96, so equal steps in
// error are equal steps in lightness and the ramp reads correctly in greyscale; the hue angle turns
// from 290 deg (violet) through red (~30) and orange (~60) to yellow (~95); chroma is
// 70 * 4t(1-t) + 30 t^2 (grey at 0, strongest in the middle, a pale yellow at 1). Colours outside
// the sRGB gamut keep their L* and hue and lose chroma until they fit. Tabulated once.
constexpr int kRampSize = 1024;

glm::dvec3 labToLinearRgb(glm::dvec3 lab) {
    const double fy = (lab.x + 16.0) / 116.0;
    const double fx = fy + lab.y / 500.0, fz = fy - lab.z / 200.0;
    auto inv = [](double f) {
        constexpr double d = 6.0 / 29.0;
        return f > d ? f * f * f : 3.0 * d * d * (f - 4.0 / 29.0);
    };
    const glm::dvec3 xyz = glm::dvec3(inv(fx), inv(fy), inv(fz)) * whiteXyz();
    return xyzToRgb() * xyz;
}

const std::array<glm::vec3, kRampSize>& ramp() {
    static const std::array<glm::vec3, kRampSize> table = [] {
        std::array<glm::vec3, kRampSize> t{};
        for (int i = 0; i < kRampSize; ++i) {
            const double s = double(i) / (kRampSize - 1);
            const double L = 4.0 + 92.0 * s;
            const double hue = (290.0 + 165.0 * s) * kPi / 180.0;
            double chroma = 70.0 * 4.0 * s * (1.0 - s) + 30.0 * s * s;
            auto rgbFor = [&](double c) { return labToLinearRgb({L, c * std::cos(hue), c * std::sin(hue)}); };
            auto inGamut = [](glm::dvec3 c) {
                return c.x >= -1e-9 && c.y >= -1e-9 && c.z >= -1e-9 && c.x <= 1 + 1e-9 && c.y <= 1 + 1e-9 &&
                       c.z <= 1 + 1e-9;
            };
            if (!inGamut(rgbFor(chroma))) {
                double lo = 0.0, hi = chroma;
                for (int it = 0; it < 40; ++it) {
                    const double mid = 0.5 * (lo + hi);
                    (inGamut(rgbFor(mid)) ? lo : hi) = mid;
                }
                chroma = lo;
            }
            const glm::dvec3 rgb = glm::clamp(rgbFor(chroma), 0.0, 1.0);
            t[size_t(i)] = glm::vec3(linearToSrgb(float(rgb.x)), linearToSrgb(float(rgb.y)), linearToSrgb(float(rgb.z)));
        }
        return t;
    }();
    return table;
}

}  // namespace

// ---------------------------------------------------------------------------------------------------

namespace flipdetail {

glm::dvec3 linearRgbToLab(glm::dvec3 rgb) {
    const glm::dvec3 n = rgbToXyz() * rgb / whiteXyz();
    const double fx = labF(n.x), fy = labF(n.y), fz = labF(n.z);
    return {116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)};
}

double huntHyab(glm::dvec3 rgbA, glm::dvec3 rgbB) {
    return hyab(huntAdjust(linearRgbToLab(rgbA)), huntAdjust(linearRgbToLab(rgbB)));
}

double colorErrorFromHyab(double distance) {
    const double e = std::pow(distance, kFlipQc);
    const double cmax = flipCmax();
    const double knee = kFlipPc * cmax;
    if (e < knee) return kFlipPt / knee * e;
    return std::min(1.0, kFlipPt + (e - knee) / (cmax - knee) * (1.0 - kFlipPt));
}

}  // namespace flipdetail

void validateImagePair(const ImageF& test, const ImageF& reference, const std::vector<uint8_t>& ignore) {
    checkImage(test, "test image");
    checkImage(reference, "reference image");
    if (test.width != reference.width || test.height != reference.height)
        throw Error("test image is " + sizeText(test) + " but the reference image is " + sizeText(reference));
    if (!ignore.empty()) {
        const size_t n = size_t(test.width) * test.height;
        if (ignore.size() != n)
            throw Error("ignore mask has " + std::to_string(ignore.size()) + " entries for " + sizeText(test) +
                        " pixels");
        if (std::all_of(ignore.begin(), ignore.end(), [](uint8_t v) { return v != 0; }))
            throw Error("ignore mask leaves out every pixel: nothing to compare");
    }
}

double meanSquaredError(const ImageF& test, const ImageF& reference, const std::vector<uint8_t>& ignore) {
    validateImagePair(test, reference, ignore);
    return mseUnchecked(test, reference, ignore);
}

double rmse(const ImageF& test, const ImageF& reference, const std::vector<uint8_t>& ignore) {
    return std::sqrt(meanSquaredError(test, reference, ignore));
}

double relativeMse(const ImageF& test, const ImageF& reference, double epsilon, const std::vector<uint8_t>& ignore) {
    validateImagePair(test, reference, ignore);
    return relMseUnchecked(test, reference, epsilon, ignore);
}

double psnrFromMse(double mse, double peak) {
    checkPeak(peak);
    if (mse <= 0.0) return std::numeric_limits<double>::infinity();
    return 10.0 * std::log10(peak * peak / mse);
}

double psnr(const ImageF& test, const ImageF& reference, double peak, const std::vector<uint8_t>& ignore) {
    checkPeak(peak);
    return psnrFromMse(meanSquaredError(test, reference, ignore), peak);
}

ErrorMap ssimMap(const ImageF& test, const ImageF& reference) {
    validateImagePair(test, reference);
    return ssimMapUnchecked(test, reference);
}

double ssim(const ImageF& test, const ImageF& reference, const std::vector<uint8_t>& ignore) {
    validateImagePair(test, reference, ignore);
    return meanOfMap(ssimMapUnchecked(test, reference), ignore);
}

ErrorMap flipMap(const ImageF& test, const ImageF& reference, double pixelsPerDegree) {
    validateImagePair(test, reference);
    return flipMapUnchecked(test, reference, pixelsPerDegree);
}

double flip(const ImageF& test, const ImageF& reference, double pixelsPerDegree, const std::vector<uint8_t>& ignore) {
    validateImagePair(test, reference, ignore);
    return meanOfMap(flipMapUnchecked(test, reference, pixelsPerDegree), ignore);
}

double meanRadiance(const ImageF& image, const std::vector<uint8_t>& ignore) {
    double sum = 0.0;
    size_t count = 0;
    const size_t n = size_t(image.width) * image.height;
    for (size_t p = 0; p < n; ++p) {
        if (!ignore.empty() && ignore[p]) continue;
        const float* c = &image.rgba[p * 4];
        sum += (double(c[0]) + c[1] + c[2]) / 3.0;
        ++count;
    }
    return count ? sum / double(count) : 0.0;
}

ImageMetrics compareImages(const ImageF& test, const ImageF& reference, const MetricOptions& o,
                           ComparisonMaps* maps) {
    validateImagePair(test, reference, o.ignore);
    ImageMetrics m;
    const double mse = mseUnchecked(test, reference, o.ignore);
    m.rmse = std::sqrt(mse);
    m.psnrLinear = psnrFromMse(mse, o.psnrPeak);
    m.relMse = relMseUnchecked(test, reference, o.relMseEpsilon, o.ignore);
    const ImageF displayTest = toneMapImage(test, o.display), displayRef = toneMapImage(reference, o.display);
    const ImageF srgbTest = encodeSrgbImage(displayTest), srgbRef = encodeSrgbImage(displayRef);
    m.psnrSrgb = psnrFromMse(mseUnchecked(srgbTest, srgbRef, o.ignore), 1.0);
    ErrorMap ssimValues = ssimMapUnchecked(srgbTest, srgbRef);
    m.ssim = meanOfMap(ssimValues, o.ignore);
    ErrorMap flipValues = flipMapUnchecked(displayTest, displayRef, o.pixelsPerDegree);
    m.flip = meanOfMap(flipValues, o.ignore);
    if (maps) {
        for (float& v : ssimValues.values) v = 1.0f - v;
        maps->ssimError = std::move(ssimValues);
        maps->flip = std::move(flipValues);
    }
    m.meanTest = meanRadiance(test, o.ignore);
    m.meanReference = meanRadiance(reference, o.ignore);
    const size_t n = size_t(test.width) * test.height;
    m.pixels = int64_t(o.ignore.empty() ? n : size_t(std::count(o.ignore.begin(), o.ignore.end(), uint8_t(0))));
    return m;
}

ErrorMetric parseErrorMetric(const std::string& name) {
    if (name == "flip") return ErrorMetric::Flip;
    if (name == "rmse") return ErrorMetric::Rmse;
    if (name == "relmse") return ErrorMetric::RelMse;
    if (name == "ssim") return ErrorMetric::Ssim;
    throw Error("unknown metric '" + name + "' (expected flip, rmse, relmse or ssim)");
}

const char* errorMetricName(ErrorMetric m) {
    switch (m) {
        case ErrorMetric::Flip: return "flip";
        case ErrorMetric::Rmse: return "rmse";
        case ErrorMetric::RelMse: return "relmse";
        case ErrorMetric::Ssim: return "ssim";
    }
    return "?";
}

ErrorMap errorMap(const ImageF& test, const ImageF& reference, ErrorMetric metric, const MetricOptions& o) {
    validateImagePair(test, reference, o.ignore);
    switch (metric) {
        case ErrorMetric::Rmse: return pixelMap(test, reference, false, 0.0);
        case ErrorMetric::RelMse:
            if (!(o.relMseEpsilon > 0.0) || !std::isfinite(o.relMseEpsilon))
                throw Error("relative MSE epsilon must be a positive number, not " + formatMetric(o.relMseEpsilon));
            return pixelMap(test, reference, true, o.relMseEpsilon);
        case ErrorMetric::Ssim: {
            ErrorMap map = ssimMapUnchecked(encodeSrgbImage(toneMapImage(test, o.display)),
                                            encodeSrgbImage(toneMapImage(reference, o.display)));
            for (float& v : map.values) v = 1.0f - v;
            return map;
        }
        case ErrorMetric::Flip:
            return flipMapUnchecked(toneMapImage(test, o.display), toneMapImage(reference, o.display),
                                    o.pixelsPerDegree);
    }
    throw Error("unknown error metric");
}

glm::vec3 heatmapColor(float t) {
    if (!(t > 0.0f)) t = 0.0f;  // NaN too
    t = std::min(t, 1.0f);
    return ramp()[size_t(std::lround(t * float(kRampSize - 1)))];
}

namespace {
int colorBarRows(int imageHeight) { return std::max(8, imageHeight / 16); }

// One opaque pixel of an sRGB-encoded colour in [0, 1].
void setPixel(ImageU8& img, int x, int y, glm::vec3 c) {
    uint8_t* px = &img.rgba[(size_t(y) * img.width + x) * 4];
    for (int k = 0; k < 3; ++k) px[k] = uint8_t(std::lround(std::clamp(c[k], 0.0f, 1.0f) * 255.0f));
    px[3] = 255;
}

// Rows [y0, y0 + rows) of `img`: the ramp from 0 (left) to its maximum (right).
void paintColorBar(ImageU8& img, int y0, int rows) {
    for (int y = std::max(y0, 0); y < std::min(y0 + rows, img.height); ++y)
        for (int x = 0; x < img.width; ++x)
            setPixel(img, x, y, heatmapColor(img.width > 1 ? float(x) / float(img.width - 1) : 1.0f));
}
}  // namespace

void overlayColorBar(ImageU8& img) {
    const int rows = std::min(colorBarRows(img.height), img.height / 4);
    if (rows < 1) return;
    const int line = img.height - rows - 1;
    if (line >= 0)
        for (int x = 0; x < img.width; ++x) std::fill_n(&img.rgba[(size_t(line) * img.width + x) * 4], 4, uint8_t(255));
    paintColorBar(img, img.height - rows, rows);
}

ImageU8 heatmapImage(const ErrorMap& map, float maxValue, bool colorBar, const std::vector<uint8_t>& ignore) {
    if (map.width <= 0 || map.height <= 0 || map.values.size() != size_t(map.width) * map.height)
        throw Error("heatmap: error map is empty or inconsistent (" + std::to_string(map.width) + "x" +
                    std::to_string(map.height) + ")");
    if (!(maxValue > 0.0f) || !std::isfinite(maxValue))
        throw Error("heatmap: maximum value must be a positive number, not " + formatMetric(maxValue));
    if (!ignore.empty() && ignore.size() != map.values.size())
        throw Error("heatmap: ignore mask has " + std::to_string(ignore.size()) + " entries for " +
                    std::to_string(map.values.size()) + " pixels");
    const int barHeight = colorBar ? colorBarRows(map.height) : 0;
    const int gap = colorBar ? 2 : 0;
    ImageU8 img;
    img.width = map.width;
    img.height = map.height + gap + barHeight;
    img.rgba.assign(size_t(img.width) * img.height * 4, 255);
    for (int y = 0; y < map.height; ++y)
        for (int x = 0; x < map.width; ++x) {
            const size_t p = size_t(y) * map.width + x;
            setPixel(img, x, y, ignored(ignore, p) ? glm::vec3(0.5f) : heatmapColor(map.values[p] / maxValue));
        }
    for (int y = map.height; y < map.height + gap; ++y)
        for (int x = 0; x < map.width; ++x) setPixel(img, x, y, glm::vec3(1.0f));
    paintColorBar(img, map.height + gap, barHeight);
    return img;
}

void writeHeatmap(const std::string& path, const ErrorMap& map, float maxValue, bool colorBar,
                  const std::vector<uint8_t>& ignore) {
    writePng(path, heatmapImage(map, maxValue, colorBar, ignore));
}

std::string formatMetric(double value, int digits) {
    if (std::isnan(value)) return "nan";
    if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*g", std::clamp(digits, 1, 17), value);
    return buf;
}

}  // namespace gis
