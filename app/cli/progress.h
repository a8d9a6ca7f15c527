// Samples done, elapsed time and ETA on stderr while a progressive render runs: redrawn in place
// on a terminal; otherwise (logs, CI) a line every couple of seconds and one at the end, so a long
// render is never silent.
#pragma once

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>

#include <unistd.h>

#include "renderer.h"

namespace gis {

class ProgressBar {
public:
    // `what` prefixes each line ("reference cornell"), `unit` follows the counts ("spp").
    explicit ProgressBar(int total, std::string what = "", std::string unit = "spp", double intervalSeconds = 2.0)
        : total_(total), what_(std::move(what)), unit_(std::move(unit)), interval_(intervalSeconds),
          start_(Clock::now()), tty_(isatty(2)) {}
    void update(int done) {
        const double elapsed = seconds();
        const double eta = done > 0 ? elapsed * (total_ - done) / done : 0.0;
        const std::string prefix = what_.empty() ? "" : what_ + ": ";
        if (tty_) {
            const int width = 30, filled = total_ > 0 ? std::min(width, width * done / total_) : width;
            std::fprintf(stderr, "\r%s[%s%s] %d/%d %s  %.1f s elapsed  ETA %.1f s ", prefix.c_str(),
                         std::string(filled, '#').c_str(), std::string(width - filled, '.').c_str(), done, total_,
                         unit_.c_str(), elapsed, eta);
        } else if (elapsed - lastPrint_ >= interval_ || done >= total_) {
            std::fprintf(stderr, "%s%d/%d %s  %.1f s elapsed  ETA %.1f s\n", prefix.c_str(), done, total_, unit_.c_str(),
                         elapsed, eta);
            lastPrint_ = elapsed;
        }
        std::fflush(stderr);
    }
    void finish() {
        if (tty_) std::fprintf(stderr, "\n");
    }

private:
    using Clock = std::chrono::steady_clock;
    double seconds() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }
    int total_;
    std::string what_, unit_;
    double interval_;
    Clock::time_point start_;
    bool tty_;
    double lastPrint_ = 0.0;
};

// Renders frames (each finished, so the bar follows the GPU) until every progressive pass is done.
inline void renderToConvergence(Renderer& renderer, ProgressBar& progress) {
    do {
        renderer.renderFrame();
        glFinish();
        progress.update(renderer.samplesDone());
    } while (!renderer.converged());
    progress.finish();
}

}  // namespace gis
