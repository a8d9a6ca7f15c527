// The scripted fly-through (renderer/camera_path.h; `render --flythrough`, `bench --flythrough`):
// the same poses on every call, inside the atrium and never looking straight up or down, the same
// images on every run, and bench rows that say what a cascade move costs.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>

#include "camera_path.h"
#include "cli_util.h"
#include "image.h"
#include "scene/scene.h"

namespace gis::test {
namespace {

bool samePose(const CameraPose& a, const CameraPose& b) { return a.position == b.position && a.forward == b.forward; }

TEST(Flythrough, GivesTheSamePosesOnEveryCall) {
    const CameraPath a = flythroughPath(loadScene("builtin:atrium").bounds);
    const CameraPath b = flythroughPath(loadScene("builtin:atrium").bounds);
    for (int i = 0; i < kFlythroughFrames; ++i) {
        EXPECT_TRUE(samePose(a.at(i, kFlythroughFrames), b.at(i, kFlythroughFrames))) << "frame " << i;
        EXPECT_TRUE(samePose(a.at(i, kFlythroughFrames), a.at(i, kFlythroughFrames))) << "frame " << i;
    }
    // A loop: one frame past the last is the first again; and the camera does move.
    EXPECT_TRUE(samePose(a.at(kFlythroughFrames, kFlythroughFrames), a.at(0, kFlythroughFrames)));
    EXPECT_GT(glm::length(a.at(1, kFlythroughFrames).position - a.at(0, kFlythroughFrames).position), 0.1f);
}

TEST(Flythrough, StaysInTheAtriumSmoothlyAndNeverLooksStraightUpOrDown) {
    const Aabb bounds = loadScene("builtin:atrium").bounds;
    const CameraPath path = flythroughPath(bounds);
    constexpr int kSamples = 1200;
    CameraPose previous = path.atParameter(0.0f);
    float pathLength = 0.0f;
    for (int i = 0; i <= kSamples; ++i) {
        const CameraPose p = path.atParameter(float(i) / kSamples);
        for (int axis = 0; axis < 3; ++axis) {
            // A metre from every side of the bounds: inside the walls, above the floor, below the roof.
            EXPECT_GT(p.position[axis], bounds.min[axis] + 1.0f) << "sample " << i << " axis " << axis;
            EXPECT_LT(p.position[axis], bounds.max[axis] - 1.0f) << "sample " << i << " axis " << axis;
        }
        // The courtyard's columns stand at |x| = 10, |z| = 6 (builtin_gi_scenes.cpp): keep clear of them.
        EXPECT_LT(std::abs(p.position.x), 9.0f) << "sample " << i;
        EXPECT_LT(std::abs(p.position.z), 5.0f) << "sample " << i;
        EXPECT_NEAR(glm::length(p.forward), 1.0f, 1e-4f);
        // lookAt with +Y up degenerates looking straight up or down: stay within 60 degrees of level.
        EXPECT_LT(std::abs(p.forward.y), std::sin(glm::radians(60.0f))) << "sample " << i;
        // Smooth: no jump in position, no snap in direction between neighbouring samples.
        EXPECT_LT(glm::length(p.position - previous.position), 0.2f) << "sample " << i;
        EXPECT_GT(glm::dot(p.forward, previous.forward), std::cos(glm::radians(5.0f))) << "sample " << i;
        pathLength += glm::length(p.position - previous.position);
        previous = p;
    }
    EXPECT_GT(pathLength, 20.0f);  // a real tour of the courtyard, not a spot
    EXPECT_THROW(flythroughPath(Aabb{}), Error);
}

// Two runs of the same fly-through write the same bytes; a longer one ends elsewhere.
TEST(Flythrough, RendersTheSameImagesOnEveryRun) {
    const std::string dir = tempDir("flythrough_images");
    // sdf with its cascades (3 on the atrium) at 32^3: each frame after the first (the warm-up
    // frame's pose) of a 6-frame loop moves the finer two.
    const std::string common = "render --scene builtin:atrium --size 64x64 --gi sdf --set sdf.resolution=32 ";
    const CliResult a = runCli(common + "--flythrough=6 --timings --out " + dir + "/a.png");
    ASSERT_EQ(a.status, 0) << a.err;
    const CliResult b = runCli(common + "--flythrough=6 --out " + dir + "/b.png");
    ASSERT_EQ(b.status, 0) << b.err;
    const ImageU8 first = readPng(dir + "/a.png"), second = readPng(dir + "/b.png");
    ASSERT_EQ(first.rgba.size(), 64u * 64u * 4u);
    EXPECT_TRUE(first.rgba == second.rgba) << "two runs of the same fly-through differ";

    const CliResult shorter = runCli(common + "--flythrough=3 --out " + dir + "/c.png");
    ASSERT_EQ(shorter.status, 0) << shorter.err;
    EXPECT_FALSE(readPng(dir + "/c.png").rgba == first.rgba) << "frame 2 of 3 and frame 5 of 6 are other views";

    // --timings: a line per frame, the summary, and the cascade moves the camera caused.
    EXPECT_NE(a.out.find("flythrough: 6 frames"), std::string::npos) << a.out;
    EXPECT_NE(a.out.find("\n5 "), std::string::npos) << a.out;
    EXPECT_NE(a.out.find("sdf/c0.voxelize"), std::string::npos) << a.out;
}

TEST(Flythrough, BenchRowsHoldTheMedianWorstFrameAndCascadeMoves) {
    const std::string dir = tempDir("flythrough_bench");
    const CliResult r = runCli("bench --flythrough=2 --scenes builtin:atrium --size 32x32 --methods none,sdf "
                               "--presets medium --out-dir " + dir);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.err.find("reference"), std::string::npos) << "a fly-through renders no reference: " << r.err;
    std::ifstream jf(dir + "/bench.json");
    const nlohmann::json j = nlohmann::json::parse(jf);
    ASSERT_EQ(j["results"].size(), 2u);
    for (const auto& row : j["results"]) {
        const auto& f = row["flythrough"];
        EXPECT_EQ(f["frames"], 2) << row.dump();
        EXPECT_GT(f["gpu_ms_median"].get<double>(), 0.0) << row.dump();
        EXPECT_GE(f["gpu_ms_worst"].get<double>(), f["gpu_ms_median"].get<double>()) << row.dump();
        EXPECT_EQ(row["gpu_ms"], f["gpu_ms_median"]);
        EXPECT_FALSE(row.contains("rmse")) << "scored against nothing: " << row.dump();
        // none has no volume. sdf's finer cascades follow the camera: frame 0 is the warm-up frame's
        // pose (nothing moves), frame 1 half the loop away (they move).
        if (row["method"] == "none") {
            EXPECT_EQ(f["move_frames"], 0) << row.dump();
            EXPECT_TRUE(f["move_gpu_ms_median"].is_null()) << row.dump();
        } else {
            EXPECT_EQ(f["move_frames"], 1) << row.dump();
            EXPECT_GT(f["move_gpu_ms_median"].get<double>(), 0.0) << row.dump();
            EXPECT_GT(f["still_gpu_ms_median"].get<double>(), 0.0) << row.dump();
        }
    }
    std::ifstream cf(dir + "/bench.csv");
    std::string header;
    std::getline(cf, header);
    EXPECT_NE(header.find("fly_worst_ms"), std::string::npos) << header;
    EXPECT_TRUE(fileExists(dir + "/atrium_grid.png"));
    EXPECT_FALSE(fileExists(dir + "/atrium_chart.png"));
}

}  // namespace
}  // namespace gis::test
