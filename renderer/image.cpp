#include "image.h"

#include <stb_image.h>
#include <stb_image_write.h>
#include <tinyexr.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <mutex>

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

// The temporary file being written, for the signal handlers: a fixed buffer and a flag, because
// a handler may only use async-signal-safe calls (unlink, sigaction, raise).
char gTmpPath[4096];
volatile sig_atomic_t gTmpActive = 0;
constexpr int kCleanupSignals[] = {SIGINT, SIGTERM, SIGHUP};
struct sigaction gOldActions[3];
struct sigaction gOldXfsz;

extern "C" void removeTmpAndReraise(int sig) {
    if (gTmpActive) ::unlink(gTmpPath);
    gTmpActive = 0;
    for (size_t i = 0; i < 3; ++i)
        if (kCleanupSignals[i] == sig) ::sigaction(sig, &gOldActions[i], nullptr);
    ::raise(sig);  // now with the previous disposition (by default: terminate)
}

// While a temporary file exists: SIGINT/SIGTERM/SIGHUP, where they would kill the process, remove
// it before the process dies, and SIGXFSZ (file size limit reached), which would kill the process
// and leave the file, is ignored so that the write fails with EFBIG and takes the ordinary error
// path. SIGKILL cannot be caught: it leaves the temporary file (never the target) behind.
class TmpFileGuard {
public:
    explicit TmpFileGuard(const std::string& tmp) {
        std::snprintf(gTmpPath, sizeof gTmpPath, "%s", tmp.c_str());
        struct sigaction sa {};
        sa.sa_handler = removeTmpAndReraise;
        sigemptyset(&sa.sa_mask);
        for (size_t i = 0; i < 3; ++i) {
            ::sigaction(kCleanupSignals[i], &sa, &gOldActions[i]);
            // Only where the signal would kill the process: one the caller ignores (nohup) stays
            // ignored, and one the caller handles (a window's graceful quit) lets the write finish.
            const bool wasDefault = !(gOldActions[i].sa_flags & SA_SIGINFO) && gOldActions[i].sa_handler == SIG_DFL;
            if (!wasDefault) ::sigaction(kCleanupSignals[i], &gOldActions[i], nullptr);
        }
        struct sigaction ign {};
        ign.sa_handler = SIG_IGN;
        sigemptyset(&ign.sa_mask);
        ::sigaction(SIGXFSZ, &ign, &gOldXfsz);
        // A path the buffer cannot hold is not armed: unlinking a truncated path could remove
        // some other file.
        gTmpActive = tmp.size() < sizeof gTmpPath;
    }
    ~TmpFileGuard() {
        gTmpActive = 0;
        for (size_t i = 0; i < 3; ++i) ::sigaction(kCleanupSignals[i], &gOldActions[i], nullptr);
        ::sigaction(SIGXFSZ, &gOldXfsz, nullptr);
    }
    TmpFileGuard(const TmpFileGuard&) = delete;
    TmpFileGuard& operator=(const TmpFileGuard&) = delete;
};

std::mutex gWriteMutex;  // one temporary file (and one set of handlers) at a time

// A file whose every write, flush and close is checked: the first failure's errno is kept and
// reported by finish(), so a full disk or a size limit is an error, never a short file.
class CheckedFile {
public:
    CheckedFile(const std::string& path, const std::string& label) : label_(label) {
        f_ = std::fopen(path.c_str(), "wb");
        if (!f_) throw Error(label_ + ": cannot create temporary file " + path + ": " + std::strerror(errno));
    }
    ~CheckedFile() {
        if (f_) std::fclose(f_);
    }
    void write(const void* data, size_t bytes) {
        if (err_ || bytes == 0) return;
        errno = 0;
        if (std::fwrite(data, 1, bytes, f_) != bytes) err_ = errno ? errno : EIO;
    }
    void finish() {
        if (!err_ && std::fflush(f_) != 0) err_ = errno ? errno : EIO;
        if (!err_ && ::fsync(fileno(f_)) != 0) err_ = errno;  // delayed errors (NFS, quotas)
        FILE* f = f_;
        f_ = nullptr;
        if (std::fclose(f) != 0 && !err_) err_ = errno ? errno : EIO;
        if (err_) throw Error(label_ + ": cannot write: " + std::strerror(err_));
    }

private:
    FILE* f_ = nullptr;
    std::string label_;
    int err_ = 0;
};

void stbWrite(void* context, void* data, int size) {
    static_cast<CheckedFile*>(context)->write(data, size_t(size));
}

}  // namespace

void writeAtomically(const std::string& path, const std::function<void(const std::string&)>& write) {
    namespace fs = std::filesystem;
    fs::path target(path);
    if (target.has_parent_path() && !fs::is_directory(target.parent_path()))
        throw Error(path + ": directory " + target.parent_path().string() + " does not exist");
    // Host and process in the temporary's name: two machines writing one file on a shared file
    // system (a bench sweep's cache) may well have the same process id.
    char host[256] = "";
    if (::gethostname(host, sizeof host - 1) != 0) host[0] = '\0';
    const std::string tmp = path + ".tmp." + host + "." + std::to_string(::getpid());
    std::lock_guard<std::mutex> lock(gWriteMutex);
    TmpFileGuard guard(tmp);
    try {
        write(tmp);
        if (std::rename(tmp.c_str(), path.c_str()) != 0)
            throw Error(path + ": cannot rename temporary file: " + std::strerror(errno));
    } catch (...) {
        ::unlink(tmp.c_str());
        throw;
    }
}

void writePng(const std::string& path, const ImageU8& image) {
    writeAtomically(path, [&](const std::string& tmp) {
        CheckedFile file(tmp, path);
        if (!stbi_write_png_to_func(stbWrite, &file, image.width, image.height, 4, image.rgba.data(),
                                    image.width * 4))
            throw Error(path + ": cannot encode PNG");
        file.finish();
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
        // Encoded in memory and written by us: tinyexr's own file writer ignores fclose's result.
        const char* err = nullptr;
        unsigned char* mem = nullptr;
        const size_t bytes = SaveEXRImageToMemory(&exr, &header, &mem, &err);
        if (bytes == 0 || !mem) {
            std::string msg = err ? err : "unknown error";
            if (err) FreeEXRErrorMessage(err);
            std::free(mem);
            throw Error(path + ": cannot encode EXR: " + msg);
        }
        CheckedFile file(tmp, path);
        file.write(mem, bytes);
        std::free(mem);
        file.finish();
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
