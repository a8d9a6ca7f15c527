// The scene volume: what every voxel-based GI method reads, built once per renderer for the
// methods that ask (SceneServices::volume) and composed here only. A method states what it needs
// (VolumeRequest) and the volume does the rest: it declares the frame resources its update reads
// and the programs it builds, brings itself up to date before the method's own work (VolumePass,
// volume/volume_pass.h) and binds itself into a method's program at its slots (volume_slots.h).
// Per cascade: the voxel grid (occupancy, albedo, normal, emission; volume/voxelizer.h), the light
// its voxels send out (volume/voxel_radiance.h) and, when asked for, a layer of the signed
// distance field jump-flooded from its surface voxels (volume/distance_field.h).
//
// What is rebuilt and when, for every method alike (invalidate()):
// - geometry: voxels, field and light;
// - materials: voxels (albedo, emission) and light; occupancy, so the field, stays;
// - lights: the light only: no voxelization and no flood;
// - the camera: only cascades it takes with it (volume_cascades.h) are rebuilt whole.
// Each step is timed under the executing pass's step timers with the names the methods report
// ("voxelize", "occupancy", "seed", "jfa.K.STEP", "resolve", "inject", "mips", "bounce"; "cN."
// before each with more than one cascade). With `occupancy`, each cascade's occupancy hierarchy
// (volume/occupancy.h) is rebuilt with its voxels.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "frame.h"
#include "gl/shader.h"
#include "volume/distance_field.h"
#include "volume/voxel_radiance.h"
#include "volume/occupancy.h"
#include "volume/volume_cascades.h"
#include "volume/volume_slots.h"

namespace gis {

// What a method asks of the volume. Two methods asking the same share one volume.
struct VolumeRequest {
    std::string method;               // "vct": the ledger's owner and the prefix of parameter names in messages
    int resolution = 64;              // cells per edge of every cascade
    std::string resolutionKey;        // the parameter that set it ("vct.resolution"), for budget messages
    // The voxelizer's rasterization; `conservativeKey` empty: the best the driver has, silently.
    ConservativeMode conservative = ConservativeMode::Hardware;
    std::string conservativeKey;
    float marginVoxels = kVolumeMarginVoxels;
    // The voxels' light: directional mips (cones), back faces left out of them, further bounces.
    bool anisotropic = false, cullBackfaces = false, mips = false;
    bool cullUnlitOutsides = false;   // surfaces facing air no light reaches leave the light (exterior.comp)
    // The tracers' hits light themselves with the punctual lights (shaders/volume/hit_light.glsl):
    // level 0 keeps the punctual lights' share of its light (VoxelRadiance::punctual).
    bool hitLights = false;
    int bounces = 1;
    bool distanceField = false;
    JfaVariant jfa = JfaVariant::OnePlusJfa;
    bool occupancy = false;           // the occupancy hierarchy (HDDA traversal)
    // The cascades' albedo in one texture, a layer each (albedoTexture()): a hit's albedo in any
    // cascade by a coordinate (the probes' multi-bounce term).
    bool albedoAtlas = false;
    bool scroll = false;              // a moved cascade voxelizes only the cells it gained
    // A second light that sums the bounce series over frames (vct.feedback: restartFeedback(),
    // addFeedbackBounce()); the tracers then read it, while the volume's own stays the injected light.
    bool feedback = false;
    // Cascades around the camera: `cascades` > 0 a fixed count, 0 from `cascadeExtent` (world
    // units), or with that 0 too, from the render camera's view depth (volume_cascades.h).
    int cascades = 1;
    float cascadeExtent = 1.0f;
    bool countFromView() const { return cascades == 0 && cascadeExtent == 0.0f; }

    bool operator==(const VolumeRequest& o) const;
};

// GPU bytes the volume will hold for `request` with `cascades` cascades (the field at its peak
// while it is built), for the budget check before anything is allocated.
int64_t sceneVolumeBytes(const VolumeRequest& request, int cascades);

// Where the cascades of the volume `request` describes lie in a scene with `bounds`, seen from a
// camera whose near view depth is `viewDepth` (read only when request.countFromView()).
CascadeLayout volumeLayout(const Aabb& bounds, const VolumeRequest& request, float viewDepth);
// The view depth volumeLayout needs for `request` from the render `settings` describe (their
// camera in `scene`): traced only when request.countFromView(), else +inf, unused.
float viewDepthFor(const VolumeRequest& request, const Scene& scene, const RenderSettings& settings);

class SceneVolume {
public:
    // Refuses (gis::Error naming request.resolutionKey) what exceeds the voxel budget, then
    // allocates; cascades are placed around the camera by the first update().
    // `viewDepth`: the render camera's (volumeLayout), when request.countFromView().
    SceneVolume(const Aabb& bounds, const VolumeRequest& request, float viewDepth, gl::MemoryLedger& ledger,
                RaySceneSource rays);
    SceneVolume(const SceneVolume&) = delete;
    SceneVolume& operator=(const SceneVolume&) = delete;

    // Brings every cascade up to date for this frame: places them around the camera, then
    // voxelizes, floods and relights what is out of date. `bounceCones` are the cones further
    // bounces gather with (the method's live setting).
    void update(Frame& frame, const ConeSettings& bounceCones = {});
    void invalidate(Changes changes);
    // What update() reads from the frame: the lights and their shadow maps, for light injection.
    static std::vector<std::string> inputs();
    // Every program a volume for `request` may build (a method's programs() lists them first).
    static std::vector<ProgramDesc> programs(const VolumeRequest& request);
    // Binds what the request holds into the next programs at the volume's slots (volume_slots.h):
    // the traced light (tracedRadiance(), or the light's layers with more than one cascade), the
    // field and its coarse level, cascade 0's albedo and emission, the occupancy buffers.
    void bind() const;
    // request.feedback: the feedback light starts over from the injected light, or gains one bounce
    // gathered with `cones` (the caller binds the environment the cones see when they leave).
    void restartFeedback();
    void addFeedbackBounce(const ConeSettings& cones);

    const VolumeRequest& request() const { return request_; }
    const CascadeLayout& layout() const { return layout_; }
    int cascadeCount() const { return layout_.count; }
    const VoxelGrid& grid(int cascade = 0) const;
    const VoxelRadiance& radiance(int cascade = 0) const;
    // The light tracers read with one cascade: the feedback light with request.feedback, else radiance().
    const VoxelRadiance& tracedRadiance() const { return feedback_ ? *feedback_ : radiance(); }
    // Level 0 of the light: the cascade's own texture with one cascade, else one layer per cascade
    // stacked along z (like the field's layers), so a tracer switches cascade by a coordinate.
    GLuint radianceTexture() const;
    GLuint sidesTexture() const;     // its slab voxels' sides (VoxelRadiance::sides), laid out the same
    GLuint albedoTexture() const;    // the voxels' albedo (a = occupancy), laid out the same; request.albedoAtlas
    const DistanceField& field() const;  // throws unless request.distanceField
    bool hasField() const { return field_ != nullptr; }
    const OccupancyHierarchy& occupancy() const;  // throws unless request.occupancy
    // Cascade i's cube as the voxels have it now.
    SdfVolume cascadeVolume(int i) const;

    // What the last update() did to a cascade: rebuilt its voxels or field, scrolled them (voxelized
    // the cells it gained), relit it, or nothing.
    enum class Update { Rebuilt, Scrolled, Relit, Cached };
    static const char* updateName(Update u);  // "rebuilt", "scrolled", "relit", "cached"
    Update lastUpdate(int cascade) const;
    glm::ivec3 offset(int cascade) const;   // in the cascade's cells from the scene cube's corner
    // How often cascade i (or all together, for -1) was voxelized (whole or scrolled), flooded and
    // lit, and how many cells were voxelized in all.
    struct Builds {
        int voxelizations = 0, scrolls = 0, fields = 0, injections = 0;
        int64_t voxelizedCells = 0;
    };
    Builds builds(int cascade = -1) const;
    // The step-name prefix of cascade i ("" with one cascade, else "cN.").
    std::string stepPrefix(int cascade) const;
    // One line per cascade for a method's stats(), alike for every method (scripts read it: the
    // method pages' per-cascade cost tables): "cascade I: R^3 cells of C (a E cube from x, y, z),
    // up to M MiB; voxelized V, field built F, lit L times; last frame U".
    std::string describeCascade(int cascade) const;

private:
    struct Cascade {
        std::unique_ptr<Voxelizer> voxelizer;   // moved with the cascade
        std::unique_ptr<VoxelRadiance> radiance;
        glm::ivec3 offset{0};
        glm::ivec3 scrollBy{0};   // a pending scroll (request.scroll) of valid voxels, in cells; 0 = none
        bool placed = false, voxelsValid = false, fieldValid = false, radianceValid = false;
        bool scrolling() const { return scrollBy != glm::ivec3(0); }
        Update lastUpdate = Update::Cached;
        Builds builds;
    };
    void place(const glm::vec3& camera);
    void refresh(Frame& frame, int cascade, const ConeSettings& bounceCones);
    void revoxelize(Frame& frame, int cascade);
    void relight(Frame& frame, int cascade, const ConeSettings& bounceCones);
    VolumeRequest request_;
    gl::MemoryScope scope_;
    RaySceneSource rays_;
    ConeSettings litWith_;  // the bounce cones the cascades' light was gathered with
    ConservativeMode mode_;
    CascadeLayout layout_;
    std::vector<Cascade> cascades_;
    std::unique_ptr<DistanceField> field_;   // one layer per cascade
    std::unique_ptr<OccupancyHierarchy> occupancy_;
    gl::Texture radianceAtlas_;              // more than one cascade: their light, a layer each
    gl::Texture sidesAtlas_;                 // and their slab voxels' sides (VoxelRadiance::sides)
    gl::Texture albedoAtlas_;                // request.albedoAtlas: and their voxels' albedo
    std::unique_ptr<VoxelRadiance> feedback_;  // request.feedback: the bounces summed so far
};

}  // namespace gis
