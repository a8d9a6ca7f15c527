#include "volume/scene_volume.h"

#include <cstdio>
#include <limits>

#include <tuple>
#include <type_traits>
#include <utility>

#include "bvh.h"

namespace gis {

namespace {
auto tied(const VolumeRequest& r) {
    return std::tie(r.method, r.resolution, r.resolutionKey, r.conservative, r.conservativeKey, r.marginVoxels,
                    r.anisotropic, r.cullBackfaces, r.cullUnlitOutsides, r.hitLights, r.mips, r.bounces, r.distanceField,
                    r.jfa, r.occupancy, r.albedoAtlas, r.scroll, r.feedback, r.cascades, r.cascadeExtent);
}

// The members of an aggregate, counted as the most values it can be brace-initialised from (C++17
// has no reflection and no defaulted ==): a member added to VolumeRequest and not to tied() would
// let two different requests share one volume, so that fails to compile instead.
struct AnyMember {
    template <class T>
    operator T() const;
};
template <class T, class... A>
constexpr auto braceInitialisable(int) -> decltype(T{std::declval<A>()...}, true) { return true; }
template <class T, class... A>
constexpr bool braceInitialisable(...) { return false; }
template <class T, class... A>
constexpr size_t memberCount() {
    if constexpr (braceInitialisable<T, A..., AnyMember>(0)) return memberCount<T, A..., AnyMember>();
    else return sizeof...(A);
}
static_assert(std::is_aggregate_v<VolumeRequest> &&
                  memberCount<VolumeRequest>() == std::tuple_size_v<decltype(tied(std::declval<VolumeRequest>()))>,
              "every member of VolumeRequest belongs in tied()");

// With more than one cascade: level 0 of every cascade's light and its slab voxels' sides (RGBA16F),
// and where asked their albedo (RGBA8), a layer each.
int64_t atlasBytes(int resolution, int cascades, bool albedo) {
    const int64_t n = resolution;
    return cascades > 1 ? (2 * 8 + (albedo ? 4 : 0)) * n * n * n * cascades : 0;
}

gl::Texture createAtlas(const gl::MemoryScope& scope, GLenum format, int n, int cascades, bool filtered) {
    gl::Texture atlas = gl::createTexture3D(scope, format, n, n, n * cascades);
    if (!filtered) return atlas;  // read by texelFetch
    glTextureParameteri(atlas.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(atlas.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    for (GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R}) glTextureParameteri(atlas.id(), wrap, GL_CLAMP_TO_EDGE);
    return atlas;
}

// Level 0 of `source` into cascade i's layer of `atlas`.
void copyIntoLayer(GLuint source, GLuint atlas, int n, int i) {
    glCopyImageSubData(source, GL_TEXTURE_3D, 0, 0, 0, 0, atlas, GL_TEXTURE_3D, 0, 0, 0, i * n, n, n, n);
}

VolumeFit fitOf(const SdfVolume& v) {
    VolumeFit fit;
    fit.origin = v.origin;
    fit.size = v.size;
    fit.resolution = v.resolution;
    return fit;
}
}  // namespace

std::vector<std::string> SceneVolume::inputs() {
    return {resource::kLights, resource::kShadowMaps, resource::kShadowCubes};
}

std::vector<ProgramDesc> SceneVolume::programs(const VolumeRequest& request) {
    std::vector<ProgramDesc> all = Voxelizer::programs();
    std::vector<std::vector<ProgramDesc>> parts{VoxelRadiance::programs()};
    if (request.distanceField) parts.push_back(DistanceField::programs());
    if (request.occupancy) parts.push_back(OccupancyHierarchy::programs());
    for (const auto& part : parts) all.insert(all.end(), part.begin(), part.end());
    return all;
}

bool VolumeRequest::operator==(const VolumeRequest& o) const { return tied(*this) == tied(o); }

int64_t sceneVolumeBytes(const VolumeRequest& r, int cascades) {
    const int n = r.resolution;
    const int64_t perCascade = voxelGridBytes(n) + voxelRadianceBytes(n, r.anisotropic, r.bounces, r.cullUnlitOutsides, r.hitLights);
    return cascades * perCascade + (r.distanceField ? distanceFieldBuildBytes(n, cascades) : 0) +
           (r.occupancy ? occupancyBytes(n, cascades) : 0) + atlasBytes(n, cascades, r.albedoAtlas);
}

CascadeLayout volumeLayout(const Aabb& bounds, const VolumeRequest& r, float viewDepth) {
    return layoutCascades(bounds, r.resolution, finestCascadeExtent(r.cascadeExtent, viewDepth), r.cascades, r.method,
                          r.marginVoxels);
}

float viewDepthFor(const VolumeRequest& request, const Scene& scene, const RenderSettings& settings) {
    if (!request.countFromView()) return std::numeric_limits<float>::infinity();
    return nearViewDepth(buildBvh(scene), cameraMatrices(scene, settings.camera,
                                                           float(settings.width) / float(std::max(1, settings.height))));
}

SceneVolume::SceneVolume(const Aabb& bounds, const VolumeRequest& request, float viewDepth, gl::MemoryLedger& ledger,
                         RaySceneSource rays)
    : request_(request), scope_{&ledger, request.method}, rays_(std::move(rays)) {
    const int n = request.resolution;
    layout_ = volumeLayout(bounds, request, viewDepth);
    const int count = layout_.count;
    // Refuse before allocating anything: the whole volume at once.
    checkVoxelBudget(n, sceneVolumeBytes(request, count), request.resolutionKey);
    mode_ = request.conservative;
    if (request.conservativeKey.empty() && mode_ == ConservativeMode::Hardware &&
        !Voxelizer::hardwareConservativeAvailable())
        mode_ = ConservativeMode::Geometry;
    cascades_.resize(size_t(count));
    // Each cascade's grid exists from the start (stats and debug views may ask before the first
    // frame), around the scene's centre until the first update() places it at the camera.
    for (int i = 0; i < count; ++i) {
        Cascade& c = cascades_[size_t(i)];
        const SdfVolume v = layout_.volume(i, layout_.centredOffset(i, layout_.scene.origin + 0.5f * layout_.scene.size));
        c.voxelizer = std::make_unique<Voxelizer>(fitOf(v), mode_, scope_, request.conservativeKey);
        c.radiance = std::make_unique<VoxelRadiance>(n, request.anisotropic, request.bounces, scope_, request.cullBackfaces,
                                                     request.cullUnlitOutsides, request.hitLights);
    }
    if (request.distanceField)
        field_ = std::make_unique<DistanceField>(layout_.volume(count - 1, glm::ivec3(0)), scope_, count);
    if (request.occupancy) occupancy_ = std::make_unique<OccupancyHierarchy>(scope_, n, count);
    if (count > 1) {
        radianceAtlas_ = createAtlas(scope_, GL_RGBA16F, n, count, true);
        sidesAtlas_ = createAtlas(scope_, GL_RGBA16F, n, count, false);
        if (request.albedoAtlas) albedoAtlas_ = createAtlas(scope_, GL_RGBA8, n, count, true);
    }
    // Two bounces: the sums and the bounce targets, no more.
    if (request.feedback)
        feedback_ = std::make_unique<VoxelRadiance>(n, request.anisotropic, 2, scope_, request.cullBackfaces, false, request.hitLights);
}

void SceneVolume::invalidate(Changes c) {
    for (Cascade& k : cascades_) {
        if (c & (ChangeGeometry | ChangeMaterials)) k.scrollBy = glm::ivec3(0);  // every cell is voxelized again
        if (c & ChangeGeometry) k.voxelsValid = k.fieldValid = false;
        if (c & ChangeMaterials) k.voxelsValid = false;  // albedo and emission; occupancy, so the field, stays
        if (c & (ChangeGeometry | ChangeMaterials | ChangeLights)) k.radianceValid = false;
    }
}

std::string SceneVolume::stepPrefix(int cascade) const {
    return layout_.count > 1 ? "c" + std::to_string(cascade) + "." : "";
}

// Cascades follow the camera beyond the snap distance (one cascade is the scene cube and never
// moves). A moved one keeps its voxelizer and is rebuilt whole at its new cube, or, when the
// request scrolls and its voxels were valid, scrolled there (revoxelize() moves the voxelizer).
void SceneVolume::place(const glm::vec3& camera) {
    for (int i = 0; i < layout_.count; ++i) {
        Cascade& c = cascades_[size_t(i)];
        const glm::ivec3 centred = layout_.centredOffset(i, camera);
        if (c.placed && !layout_.mustMove(c.offset, centred)) continue;
        c.scrollBy = request_.scroll && c.placed && c.voxelsValid ? centred - c.offset : glm::ivec3(0);
        c.offset = centred;
        c.placed = true;
        if (field_) field_->setVolume(i, layout_.volume(i, centred));
        c.voxelsValid = c.fieldValid = c.radianceValid = false;
    }
}

void SceneVolume::revoxelize(Frame& frame, int i) {
    Cascade& c = cascades_[size_t(i)];
    const std::string prefix = stepPrefix(i);
    const int n = layout_.resolution();
    const VolumeFit fit = fitOf(layout_.volume(i, c.offset));
    if (c.scrolling()) {
        auto t = frame.step(prefix + "voxelize");
        c.builds.voxelizedCells += c.voxelizer->scroll(fit, c.scrollBy, frame.scene);
        ++c.builds.scrolls;
    } else {
        c.voxelizer->moveTo(fit);
        voxelizeFrame(frame, *c.voxelizer, prefix);
        c.builds.voxelizedCells += int64_t(n) * n * n;
        ++c.builds.voxelizations;
    }
    c.scrollBy = glm::ivec3(0);
    if (albedoAtlas_.id()) {
        glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
        copyIntoLayer(c.voxelizer->grid().albedo.id(), albedoAtlas_.id(), n, i);
    }
    if (occupancy_) {
        auto t = frame.step(prefix + "occupancy");
        occupancy_->build(c.voxelizer->grid(), i);
    }
}

void SceneVolume::update(Frame& frame, const ConeSettings& bounceCones) {
    place(frame.camera.position);
    // The bounces gather with the method's live cone settings (vct.cones, vct.sky-rays ...): a
    // change gathers again.
    if (request_.bounces > 1 && !(bounceCones == litWith_))
        for (Cascade& c : cascades_) c.radianceValid = false;
    litWith_ = bounceCones;
    for (int i = 0; i < layout_.count; ++i) refresh(frame, i, bounceCones);
}

void SceneVolume::refresh(Frame& frame, int i, const ConeSettings& bounceCones) {
    Cascade& c = cascades_[size_t(i)];
    const std::string prefix = stepPrefix(i);
    const bool fieldStale = field_ && !c.fieldValid;
    c.lastUpdate = !c.voxelsValid && c.scrolling() ? Update::Scrolled
                   : !c.voxelsValid || fieldStale   ? Update::Rebuilt
                   : !c.radianceValid               ? Update::Relit
                                                    : Update::Cached;
    if (!c.voxelsValid) {
        revoxelize(frame, i);
        c.voxelsValid = true;
        c.radianceValid = false;
    }
    if (fieldStale) {
        const VoxelGrid& grid = c.voxelizer->grid();
        // Seeds: the voxelizer's occupancy (albedo alpha) and averaged normals (the field's sign).
        field_->build({grid.albedo.id(), grid.normal.id()}, request_.jfa, frame.steps, i, prefix);
        ++c.builds.fields;
    }
    c.fieldValid = true;
    if (!c.radianceValid) relight(frame, i, bounceCones);
    c.radianceValid = true;
}

void SceneVolume::relight(Frame& frame, int i, const ConeSettings& bounceCones) {
    Cascade& c = cascades_[size_t(i)];
    const VoxelGrid& grid = c.voxelizer->grid();
    const std::string prefix = stepPrefix(i);
    injectFrameLights(frame, grid, *c.radiance, rays_, prefix);
    ++c.builds.injections;
    // Further bounces gather by cone tracing the mips in voxel space.
    if (request_.mips || request_.bounces > 1) {
        auto t = frame.step(prefix + "mips");
        c.radiance->buildMips(grid);
    }
    if (request_.bounces > 1) {
        auto t = frame.step(prefix + "bounce");
        frame.bindEnvironment();
        c.radiance->bounce(grid, bounceCones, bounceCones.rays > 0 ? &rays_() : nullptr);
    }
    if (layout_.count > 1) {  // into this cascade's layer, where tracers read it
        const int n = layout_.resolution();
        glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
        copyIntoLayer(c.radiance->radiance().id(), radianceAtlas_.id(), n, i);
        copyIntoLayer(c.radiance->sides().id(), sidesAtlas_.id(), n, i);
    }
}

const VoxelGrid& SceneVolume::grid(int cascade) const { return cascades_.at(size_t(cascade)).voxelizer->grid(); }

const VoxelRadiance& SceneVolume::radiance(int cascade) const { return *cascades_.at(size_t(cascade)).radiance; }

GLuint SceneVolume::radianceTexture() const {
    return layout_.count > 1 ? radianceAtlas_.id() : cascades_[0].radiance->radiance().id();
}

GLuint SceneVolume::sidesTexture() const {
    return layout_.count > 1 ? sidesAtlas_.id() : cascades_[0].radiance->sides().id();
}

GLuint SceneVolume::albedoTexture() const {
    if (!request_.albedoAtlas) throw Error("scene volume: " + request_.method + " asked for no albedo atlas");
    return layout_.count > 1 ? albedoAtlas_.id() : grid().albedo.id();
}

void SceneVolume::bind() const {
    glBindSamplers(kVolumeDistanceUnit, kVolumePunctualUnit + 1 - kVolumeDistanceUnit, nullptr);
    if (layout_.count > 1) {
        glBindTextureUnit(kVolumeRadianceUnit, radianceAtlas_.id());
        glBindTextureUnit(kVolumeRadianceUnit + kVolumeRadianceUnits - 1, sidesAtlas_.id());
        glBindTextureUnit(kVolumePunctualUnit, 0);  // the cascades' rays keep their voxels' light
    } else {
        tracedRadiance().bind();
    }
    if (field_) field_->bind(kVolumeDistanceUnit);
    const GLuint voxels[2] = {grid().albedo.id(), grid().emission.id()};
    glBindTextures(kVolumeAlbedoUnit, 2, voxels);
    if (occupancy_) occupancy_->bind();
}

void SceneVolume::restartFeedback() {
    if (!feedback_) throw Error("scene volume: " + request_.method + " asked for no feedback");
    feedback_->restartFeedback(grid(), radiance());
}

void SceneVolume::addFeedbackBounce(const ConeSettings& cones) {
    if (!feedback_) throw Error("scene volume: " + request_.method + " asked for no feedback");
    feedback_->feedbackBounce(grid(), cones, cones.rays > 0 ? &rays_() : nullptr);
}

const DistanceField& SceneVolume::field() const {
    if (!field_) throw Error("scene volume: " + request_.method + " asked for no distance field");
    return *field_;
}

const OccupancyHierarchy& SceneVolume::occupancy() const {
    if (!occupancy_) throw Error("scene volume: " + request_.method + " asked for no occupancy hierarchy");
    return *occupancy_;
}

SdfVolume SceneVolume::cascadeVolume(int i) const {
    const VolumeFit& f = grid(i).fit;
    return {f.origin, f.size, f.resolution};
}

SceneVolume::Update SceneVolume::lastUpdate(int cascade) const { return cascades_.at(size_t(cascade)).lastUpdate; }

const char* SceneVolume::updateName(Update u) {
    return u == Update::Rebuilt ? "rebuilt" : u == Update::Scrolled ? "scrolled" : u == Update::Relit ? "relit" : "cached";
}

glm::ivec3 SceneVolume::offset(int cascade) const { return cascades_.at(size_t(cascade)).offset; }

std::string SceneVolume::describeCascade(int i) const {
    const SdfVolume v = cascadeVolume(i);
    const Builds b = builds(i);
    const double mib = double(sceneVolumeBytes(request_, layout_.count)) / layout_.count / (1024.0 * 1024.0);
    char line[240];
    std::snprintf(line, sizeof line,
                  "cascade %d: %d^3 cells of %.4g (a %.4g cube from %.4g, %.4g, %.4g), up to %.2f MiB; voxelized %d, "
                  "field built %d, lit %d times; last frame %s",
                  i, v.resolution, double(v.cellSize()), double(v.size), double(v.origin.x), double(v.origin.y),
                  double(v.origin.z), mib, b.voxelizations + b.scrolls, b.fields, b.injections,
                  updateName(lastUpdate(i)));
    return line;
}

SceneVolume::Builds SceneVolume::builds(int cascade) const {
    if (cascade >= 0) return cascades_.at(size_t(cascade)).builds;
    Builds sum;
    for (const Cascade& c : cascades_) {
        sum.voxelizations += c.builds.voxelizations;
        sum.scrolls += c.builds.scrolls;
        sum.voxelizedCells += c.builds.voxelizedCells;
        sum.fields += c.builds.fields;
        sum.injections += c.builds.injections;
    }
    return sum;
}

}  // namespace gis
