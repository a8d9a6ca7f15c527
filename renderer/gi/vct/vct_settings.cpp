#include "gi/vct/vct_settings.h"

#include "volume/scene_volume.h"

namespace gis {

// What VCT asks of the scene volume. With back faces culled the margin is half a voxel: the
// margin's empty voxels make coarse texels at the bounds partly transparent, and cones escape
// through them (the emissive furnace loses 26% at 32^3, 13% at 64^3 with the full margin and back
// faces culled; 7% and 3% with half a voxel). The opaque mode keeps the full margin, which its
// measured tuning (renderer/gi/vct/README.md) was made with: there its cones' own surfaces stand in
// for the loss.
VolumeRequest vctVolumeRequest(const VctSettings& s) {
    VolumeRequest r;
    r.method = "vct";
    r.resolution = s.resolution;
    r.resolutionKey = "vct.resolution";
    r.conservative = s.conservativeMode();
    r.conservativeKey = s.conservativeAsked() ? "vct.conservative" : "";
    r.cullBackfaces = s.backfaces == 1;
    r.cullUnlitOutsides = s.unlitOutsides == 0;
    r.hitLights = true;  // its rays' hits (vct.sky-rays, a live parameter)
    r.marginVoxels = r.cullBackfaces ? 0.5f : kVolumeMarginVoxels;
    r.anisotropic = s.anisotropic;
    r.mips = true;
    // With feedback the volume holds the injected light only: the pass sums the bounces itself.
    r.bounces = s.feedback ? 1 : s.bounces;
    return r;
}

int maxVctResolution() {
    static const int largest = [] {
        VctSettings smallest;  // no directional mips, one bounce: the least a volume of a size holds
        smallest.anisotropic = false;
        smallest.bounces = 1;
        smallest.unlitOutsides = 1;
        smallest.resolution = 8;
        auto fits = [&](int n) {
            VctSettings s = smallest;
            s.resolution = n;
            const VolumeRequest r = vctVolumeRequest(s);
            return sceneVolumeBytes(r, r.cascades) <= kVoxelBudgetBytes;
        };
        while (fits(smallest.resolution * 2)) smallest.resolution *= 2;
        return smallest.resolution;
    }();
    return largest;
}

const ParamTable<VctSettings>& vctParams() {
    using S = VctSettings;
    using U = ParamUpdate;
    static const ParamTable<S> table = ParamTable<S>()
        .integer(&S::resolution, "resolution", "Resolution",
                 "voxels per edge (a power of two; twice the largest would exceed the " +
                     std::to_string(kVoxelBudgetBytes >> 30) + " GiB a voxel method may hold)",
                 8, maxVctResolution(), U::Rebuild)
        .choice(&S::conservative, "conservative", "Conservative raster",
                "auto = hardware where the driver has it, else geometry; hardware = GL_NV_conservative_raster "
                "(falls back to geometry with a warning), geometry = dilation in the geometry shader, off = plain "
                "rasterization",
                {"auto", "hardware", "geometry", "off"}, U::Rebuild)
        .boolean(&S::anisotropic, "anisotropic", "Anisotropic mips", "six directional mip chains", U::Rebuild)
        .choice(&S::backfaces, "backfaces", "Back faces",
                "opaque = a voxel occludes and shows its light to cones from every side (a cone sees part of its own "
                "surface); cull = the directional mips leave out voxels a cone meets from behind (needs anisotropic)",
                {"opaque", "cull"}, U::Rebuild)
        .choice(&S::unlitOutsides, "unlit-outsides", "Unlit outsides",
                "cull = surfaces facing air that no light reaches (the outsides of a closed, lit room) leave the volume: "
                "a coarse cone texel holding a wall otherwise shows its dark outside to the room's cones; keep = voxelized "
                "as they are",
                {"cull", "keep"}, U::Rebuild)
        .integer(&S::bounces, "bounces", "Bounces", "1 = direct light and emission; more gather in voxel space again", 1,
                 4, U::Rebuild)
        .boolean(&S::feedback, "feedback", "Bounce feedback",
                 "every update gathers once more from the last result, adding a bounce, until the bounces left "
                 "are below 1% (the scene's albedo says how many updates); vct.bounces is then unused",
                 U::Rebuild)
        .choice(&S::coneSet, "cones", "Diffuse cones",
                "six 60-degree cones (Godot's set), four 90-degree cones, or many: 32 cones of 14 degrees spread by "
                "cosine (closer to the path tracer, 8x the trace)",
                {"six", "four", "many"}, U::Live)
        .real(&S::stepFactor, "step", "Step", "step as a fraction of the cone's diameter", 0.05, 2.0, U::Live)
        .real(&S::maxDistance, "max-distance", "Max distance",
              "diffuse cones' length as a fraction of the volume's edge (the specular cone goes at least the edge)",
              0.01, 2.0, U::Live)
        .real(&S::offset, "offset", "Self-occlusion offset", "start offset along the normal, in voxels", 0.0, 8.0,
              U::Live)
        .real(&S::intensity, "intensity", "Intensity", "scales the indirect terms", 0.0, 16.0, U::Live)
        .boolean(&S::specular, "specular", "Specular cone", "trace the specular cone", U::Live)
        .real(&S::specularRoughness, "specular-roughness", "Specular cone up to roughness",
              "above this roughness the specular term takes the diffuse cones' result instead of a cone of its own",
              0.0, 1.0, U::Live)
        .integer(&S::skyRays, "sky-rays", "Sky rays per cone",
                 "rays per diffuse cone through the scene's triangles in place of the cones' march (spread by cosine "
                 "over the hemisphere; as many for the voxel bounces): each brings the light of the voxel holding the "
                 "surface it meets, or the environment where it leaves the scene; 0 = the cones march through the "
                 "voxel mips (coarse voxels let the sky and the light beyond thin walls through)",
                 0, 16, U::Live)
        .choice(&S::traceScale, "trace-scale", "Trace scale",
                "full-resolution pixels per traced texel per axis: 1 = every pixel; 2 and 4 trace a quarter or a "
                "sixteenth of them, upsampled by depth and normal and gathered over jittered frames",
                {"1", "2", "4"}, U::Rebuild)
        .choice(&S::debugChannel, "debug-channel", "Debug channel", "what vct.voxels and vct.slice show",
                {"albedo", "emission", "radiance", "occupancy"}, U::Live)
        .integer(&S::debugLevel, "debug-level", "Debug mip level", "mip level for radiance and occupancy", 0, 9,
                 U::Live)
        .choice(&S::sliceAxis, "slice-axis", "Slice axis", "axis vct.slice cuts across", {"x", "y", "z"}, U::Live)
        .real(&S::slicePosition, "slice-position", "Slice position", "where along the axis, 0..1", 0.0, 1.0, U::Live);
    return table;
}

void checkVctSettings(const VctSettings& s) {
    const int r = s.resolution;
    if (r < 8 || r > maxVctResolution() || (r & (r - 1)) != 0)
        throw Error("vct.resolution: " + std::to_string(r) + " must be a power of two in [8, " +
                    std::to_string(maxVctResolution()) + "]");
    // The albedo and emission grids have no mip chain: their view at a coarser level is black.
    if (s.debugLevel > 0 && s.debugChannel < 2)
        throw Error("vct.debug-level " + std::to_string(s.debugLevel) + ": the " +
                    (s.debugChannel == 0 ? "albedo" : "emission") +
                    " grid exists at level 0 only (use vct.debug-channel=radiance or occupancy)");
}

}  // namespace gis
