#include "cli/flythrough.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <map>

#include "camera_path.h"
#include "renderer.h"

namespace gis {

namespace {

bool endsWith(const std::string& s, const std::string& suffix) {
    return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// Reads the GPU timers of the frame just rendered (after glFinish every query is done): the
// passes' new samples summed, and the voxelize steps that gained one.
class FrameTimers {
public:
    explicit FrameTimers(const Renderer& renderer) : renderer_(renderer) {}
    void read(FlythroughFrame& out) {
        for (const auto& pass : renderer_.passes()) {
            pass->timer.collect(true);
            const auto& s = pass->timer.samples;
            size_t& seen = seen_[pass->name()];
            for (; seen < s.size(); ++seen) out.gpuMs += s[seen];
            for (const auto& [step, timer] : pass->steps.steps) {
                timer->collect(true);
                const std::string name = std::string(pass->name()) + "/" + step;
                size_t& stepSeen = seen_[name];
                if (timer->samples.size() > stepSeen && endsWith(step, "voxelize")) out.rebuilt.push_back(name);
                stepSeen = timer->samples.size();
            }
        }
    }

private:
    const Renderer& renderer_;
    std::map<std::string, size_t> seen_;  // samples already read, per pass and step
};

std::string msText(double ms) {  // -1: no such frame
    if (ms < 0.0) return "-";
    char text[32];
    std::snprintf(text, sizeof text, "%.3f", ms);
    return text;
}

}  // namespace

std::vector<FlythroughFrame> flyThrough(Renderer& renderer, const Aabb& bounds, int frames) {
    const CameraPath path = flythroughPath(bounds);
    const float aspect = float(renderer.settings().width) / float(renderer.settings().height);
    FrameTimers timers(renderer);
    std::vector<FlythroughFrame> out;
    for (int i = -1; i < frames; ++i) {  // -1: the warm-up frame at the first pose
        renderer.setCamera(poseMatrices(path.at(std::max(i, 0), frames), bounds, aspect));
        FlythroughFrame frame;
        const auto t0 = std::chrono::steady_clock::now();
        renderer.renderFrame();
        glFinish();
        frame.wallMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
        timers.read(frame);
        if (i >= 0) out.push_back(frame);
    }
    return out;
}

FlythroughStats summarizeFlythrough(const std::vector<FlythroughFrame>& frames) {
    FlythroughStats s;
    s.frames = int(frames.size());
    std::vector<double> gpu, wall, move, still;
    for (const FlythroughFrame& f : frames) {
        gpu.push_back(f.gpuMs);
        wall.push_back(f.wallMs);
        (f.rebuilt.empty() ? still : move).push_back(f.gpuMs);
    }
    s.medianMs = median(gpu);
    s.worstMs = gpu.empty() ? 0.0 : *std::max_element(gpu.begin(), gpu.end());
    s.medianWallMs = median(wall);
    s.moveFrames = int(move.size());
    if (!move.empty()) s.moveMedianMs = median(move);
    if (!still.empty()) s.stillMedianMs = median(still);
    return s;
}

void printFlythrough(const std::vector<FlythroughFrame>& frames) {
    std::printf("%-6s %10s %10s  %s\n", "frame", "GPU ms", "wall ms", "cascades rebuilt");
    for (size_t i = 0; i < frames.size(); ++i) {
        std::string rebuilt;
        for (const std::string& r : frames[i].rebuilt) rebuilt += (rebuilt.empty() ? "" : ", ") + r;
        std::printf("%-6zu %10.3f %10.3f  %s\n", i, frames[i].gpuMs, frames[i].wallMs, rebuilt.c_str());
    }
    const FlythroughStats s = summarizeFlythrough(frames);
    std::printf("flythrough: %d frames, GPU ms median %.3f, worst %.3f (wall median %.3f); %d rebuilt a cascade "
                "(median %s ms), %d did not (median %s ms)\n",
                s.frames, s.medianMs, s.worstMs, s.medianWallMs, s.moveFrames, msText(s.moveMedianMs).c_str(),
                s.frames - s.moveFrames, msText(s.stillMedianMs).c_str());
}

}  // namespace gis
