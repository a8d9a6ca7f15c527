// The atlas on real models and built-in scenes: every layout valid, and the measured table of
// renderer/lightmap/README.md (lines tagged LIGHTMAP-TABLE:
// build/tests/lightmap/gis_lightmap_tests --gtest_filter='AtlasModels.*' | grep LIGHTMAP-TABLE).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>

#include <gtest/gtest.h>

#include "lightmap_test_util.h"

using namespace lmtest;

namespace {

struct Row {
    Atlas atlas;
    double ms = 0.0;
};

// Builds the atlas of `spec`, checks its layout and prints its row of the table.
Row measure(const std::string& spec, const AtlasParams& p) {
    const gis::Scene scene = gis::loadScene(spec);
    const std::vector<MeshInput> in = gis::lightmap::meshesFromScene(scene);
    const auto t0 = std::chrono::steady_clock::now();
    Row r{gis::lightmap::buildAtlas(in, p), 0.0};
    r.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    size_t tris = 0, fileUv = 0;
    for (const MeshInput& m : in) tris += m.indices.size() / 3;
    for (const auto& m : r.atlas.meshes) fileUv += m.fileUvs ? 1 : 0;
    std::vector<double> ratios = densityRatios(r.atlas, in);
    std::sort(ratios.begin(), ratios.end());
    std::string sizes;
    for (int s : r.atlas.atlasSizes) sizes += (sizes.empty() ? "" : "+") + std::to_string(s);
    const std::string name = spec.rfind("builtin:", 0) == 0 ? spec : spec.substr(spec.find_last_of('/') + 1);
    double rects = 0.0, atlasArea = 0.0;
    for (const auto& c : r.atlas.charts) rects += double(c.width) * c.height;
    for (int s : r.atlas.atlasSizes) atlasArea += double(s) * s;
    std::printf("LIGHTMAP-TABLE | %s | %.0f | %zu | %zu | %zu | %zu | %s | %.2f | %.2f | %.2f | %.1f |\n",
                name.c_str(), double(p.texelsPerMetre), in.size(), tris, r.atlas.charts.size(),
                r.atlas.atlasSizes.size(), sizes.c_str(), r.atlas.fill(), rects / atlasArea,
                ratios.empty() ? 0.0 : ratios[ratios.size() / 2], r.ms);
    size_t collapsed = 0;
    expectValidLayout(r.atlas, &collapsed);
    EXPECT_LE(collapsed * 1000, tris) << "triangles too small for float UVs";
    std::printf("  (%zu meshes with usable TEXCOORD_1, %zu triangles under float UV precision; hash %s)\n", fileUv,
                collapsed, r.atlas.hash.c_str());
    return r;
}

bool have(const std::string& path) { return std::ifstream(path).good(); }

std::string gltf(const std::string& rel) { return std::string(GIS_SHARED_DIR) + "/assets/gltf/" + rel; }

}  // namespace

TEST(AtlasModels, Table) {
    std::printf("LIGHTMAP-TABLE | scene | texels/m | meshes | triangles | charts | atlases | sizes | fill | "
                "rectangles | median density ratio | ms |\n");
    std::printf("LIGHTMAP-TABLE |---|---|---|---|---|---|---|---|---|---|---|\n");
    // The defaults on every scene; then how charts, fill and time change with the density (the
    // chart count stays, small charts stop being mostly gutter) and with the triangle count.
    const std::pair<std::string, float> rows[] = {
        {"builtin:cornell", 16.0f},
        {"builtin:atrium", 16.0f},
        {gltf("BoxTextured/glTF/BoxTextured.gltf"), 16.0f},
        {gltf("DamagedHelmet/glTF-Binary/DamagedHelmet.glb"), 16.0f},
        {gltf("nvpro_CornellBox/cornellBox.gltf"), 16.0f},
        {"builtin:cornell", 4.0f},
        {"builtin:cornell", 64.0f},
        {gltf("DamagedHelmet/glTF-Binary/DamagedHelmet.glb"), 128.0f},
        {"builtin:atrium?detail=3", 16.0f},
    };
    for (const auto& [spec, density] : rows) {
        if (spec.rfind("builtin:", 0) != 0 && !have(spec)) {
            std::printf("  %s: not in the shared folder, skipped\n", spec.c_str());
            continue;
        }
        AtlasParams p;
        p.texelsPerMetre = density;
        measure(spec, p);
    }
}

// The box of glTF samples is a cube of six faces: six charts, as for our own cube.
TEST(AtlasModels, BoxTexturedGivesSixCharts) {
    const std::string path = gltf("BoxTextured/glTF/BoxTextured.gltf");
    if (!have(path)) GTEST_SKIP() << path << " not in the shared folder";
    const Atlas a = gis::lightmap::buildAtlas(gis::lightmap::meshesFromScene(gis::loadScene(path)), AtlasParams{});
    EXPECT_EQ(a.charts.size(), 6u);
    expectValidLayout(a);
}
