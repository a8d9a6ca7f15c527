// The GI-method plug-in contract: a method defined entirely in this file is registered through the
// same registry call as the built-ins and shows up everywhere a method is listed (`methods`, --set,
// settings JSON, the panel's method list, a bench row); its "indirect.diffuse" lights the image
// exactly as the lighting contract says; every parameter row of every method round-trips and
// validates with one message format; change tracking keeps view-independent work across camera
// moves; debug views and honest timings.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include <glm/gtc/matrix_transform.hpp>

#include "cli_util.h"
#include "cli/commands.h"
#include "gi/method.h"
#include "gl/shader.h"
#include "render_test_util.h"
#include "cli/panel_action.h"
#include "cli/settings_io.h"
#include "view/view_session.h"
#include "cli/view_state.h"
#include "lights.h"
#include "uniforms.h"

namespace gis::test {
namespace {

namespace fs = std::filesystem;

// --- The test-only method: a constant indirect radiance (live) given as "indirect.diffuse".
struct ConstantSettings {
    glm::vec3 radiance{0.25f, 0.5f, 1.0f};
    int resolutionDivisor = 1;   // a rebuild parameter: the texture's size
};

const ParamTable<ConstantSettings>& constantParams() {
    using S = ConstantSettings;
    static const ParamTable<S> table = ParamTable<S>()
        .colour(&S::radiance, "radiance", "Indirect radiance", "constant incoming radiance", 1e4, ParamUpdate::Live)
        .integer(&S::resolutionDivisor, "divisor", "Divisor", "texture at 1/divisor resolution", 1, 8,
                 ParamUpdate::Rebuild);
    return table;
}

class ConstantIndirectPass final : public Pass {
public:
    ConstantIndirectPass(const RenderSettings& s, gl::MemoryLedger& ledger) {
        const int d = constantParams().read("test-constant", s.params).resolutionDivisor;
        texture_ = gl::createTexture2D({&ledger, name()}, GL_RGBA32F, std::max(1, s.width / d),
                                       std::max(1, s.height / d));
    }
    const char* name() const override { return "test-constant"; }
    std::vector<std::string> outputs() const override { return {"indirect.diffuse"}; }
    void execute(Frame& frame) override {
        auto step = frame.step("fill");
        const glm::vec3 L = constantParams().read("test-constant", frame.settings.params).radiance;
        const float value[4] = {L.r, L.g, L.b, 1.0f};
        glClearTexImage(texture_.id(), 0, GL_RGBA, GL_FLOAT, value);
        frame.put("indirect.diffuse", texture_);
        ++executions;
    }
    int executions = 0;

private:
    gl::Texture texture_;
};

int constructions = 0;

void registerConstantMethod() {
    if (findGiMethod("test-constant")) return;
    GiMethod m;
    m.name = "test-constant";
    m.summary = "test only: a constant indirect radiance";
    m.params = constantParams().rows;
    for (const std::string& p : presetNames())
        m.presets.push_back({p, "constant", {{"test-constant.divisor", ParamValue{p == "low" ? 2.0 : 1.0}}}});
    m.addPasses = [](MethodBuild& b) {
        ++constructions;
        b.add(std::make_unique<ConstantIndirectPass>(b.settings, b.ledger));
    };
    registerGiMethod(m);
}

// A white-or-grey ideal Lambert floor seen from above, nothing else: no lights, no ambient.
Scene floorScene(glm::vec3 albedo) {
    Scene scene;
    scene.name = "floor";
    scene.materials.push_back(lambert(albedo));
    addQuad(scene, glm::vec3(0.0f), glm::vec3(0, 1, 0), 2.0f, 0);
    scene.cameras.push_back(lookAtCamera(glm::vec3(0, 2, 0.001f), glm::vec3(0.0f), 30.0f));
    finalizeScene(scene);
    return scene;
}

std::string captureStdout(const std::function<void()>& run) {
    testing::internal::CaptureStdout();
    run();
    return testing::internal::GetCapturedStdout();
}

TEST(Methods, RegistryListsTheBuiltinsInOrder) {
    std::vector<std::string> names;
    for (const GiMethod& m : giMethods()) names.push_back(m.name);
    ASSERT_GE(names.size(), 4u);
    EXPECT_EQ(std::vector<std::string>(names.begin(), names.begin() + 4),
              (std::vector<std::string>{"none", "ssao", "ao-reference", "pathtrace"}));
    for (const GiMethod& m : giMethods()) {
        EXPECT_TRUE(m.addPasses) << m.name;
        for (const std::string& p : presetNames()) EXPECT_NO_THROW(m.preset(p)) << m.name << " " << p;
    }
    EXPECT_THROW(registerGiMethod(giMethod("none")), Error) << "a taken name is refused";
    EXPECT_THROW(giMethod("frobnicate"), Error);
}

TEST(Methods, ATestMethodAppearsEverywhereAMethodIsListed) {
    registerConstantMethod();
    // `gisandbox methods` and `gisandbox methods NAME`.
    const std::string list = captureStdout([] { runMethods({}); });
    EXPECT_NE(list.find("test-constant"), std::string::npos) << list;
    const std::string params = captureStdout([] { runMethods({"test-constant", false}); });
    EXPECT_NE(params.find("test-constant.radiance"), std::string::npos) << params;
    EXPECT_NE(params.find("colour"), std::string::npos);
    EXPECT_NE(params.find("test-constant.divisor"), std::string::npos);
    EXPECT_NE(params.find("rebuild"), std::string::npos);
    // --set, and its validation message.
    RenderSettings s;
    s.gi = "test-constant";
    setParam(s, "test-constant.radiance", "0.5,0.25,2");
    EXPECT_EQ(getParam(s, "test-constant.radiance").colour, glm::vec3(0.5f, 0.25f, 2.0f));
    try {
        setParam(s, "test-constant.divisor", "9");
        ADD_FAILURE() << "out of range accepted";
    } catch (const Error& e) {
        EXPECT_STREQ(e.what(), "test-constant.divisor: '9' is out of range [1, 8]");
    }
    // The panel's method list and a pane's settings JSON.
    const std::vector<std::string> choices = view::methodChoices();
    EXPECT_NE(std::find(choices.begin(), choices.end(), "test-constant"), choices.end());
    view::ViewState state;
    view::applyPanelAction(state, view::PanelAction::method(0, "test-constant"));
    view::applyPanelAction(state, view::PanelAction::param(0, "test-constant.radiance", "3,2,1"));
    view::ViewState loaded;
    view::viewStateFromJson(nlohmann::json::parse(view::viewStateToJson(state).dump()), loaded);
    EXPECT_EQ(loaded.panes[0].gi, "test-constant");
    EXPECT_EQ(loaded.panes[0].params, state.panes[0].params);
    EXPECT_EQ(getParam(view::paneSettings(loaded, 0, {8, 8}), "test-constant.radiance").colour, glm::vec3(3, 2, 1));
}

TEST(Methods, ATestMethodGetsABenchRow) {
    registerConstantMethod();
    const std::string dir = tempDir("bench_test_method");
    BenchOptions o;
    o.scenes = {"builtin:cornell"};
    o.size = "16x16";
    o.frames = 2;
    o.warmup = 1;
    o.methods = {"test-constant"};
    o.presets = {"low"};
    o.referenceSpp = 4;
    o.outDir = dir;
    o.useCurrentContext = true;  // keep the test binary's context (a second one would end it)
    context();
    ASSERT_EQ(runBench(o), 0);
    std::ifstream csv(dir + "/bench.csv");
    std::string header, row;
    std::getline(csv, header);
    std::getline(csv, row);
    EXPECT_NE(row.find(",test-constant,low,"), std::string::npos) << row;
}

// The lighting contract: with indirect.diffuse = L and nothing else, an ideal Lambert surface of
// albedo a reflects exactly a * L (E = pi L, f = a / pi).
TEST(Methods, IndirectDiffuseLightsALambertFloorAsTheContractSays) {
    registerConstantMethod();
    context();
    for (glm::vec3 albedo : {glm::vec3(1.0f), glm::vec3(0.5f, 0.25f, 0.8f)}) {
        const Scene scene = floorScene(albedo);
        RenderSettings s;
        s.width = s.height = 32;
        s.gi = "test-constant";
        s.ambient = glm::vec3(0.0f);
        s.hdr32 = true;
        const glm::vec3 L(0.25f, 0.5f, 4.0f);
        setParam(s, "test-constant.radiance", "0.25,0.5,4");
        const ImageF img = renderHdr(scene, s);
        // The G-buffer stores base colour as sRGB8 (the GPU may round either way: one step is under
        // 1% at these albedos); white is exact.
        const bool white = albedo == glm::vec3(1.0f);
        int floorPixels = 0;
        for (int y = 0; y < 32; ++y)
            for (int x = 0; x < 32; ++x) {
                const float* p = img.at(x, y);
                if (p[0] == 0.0f && p[1] == 0.0f && p[2] == 0.0f) continue;  // background is black
                ++floorPixels;
                for (int c = 0; c < 3; ++c)
                    ASSERT_NEAR(p[c], albedo[c] * L[c], (white ? 1e-5f : 1e-2f) * albedo[c] * L[c]) << x << "," << y;
                for (int c = 0; c < 3; ++c) ASSERT_EQ(p[c], img.at(16, 16)[c]) << "not uniform at " << x << "," << y;
            }
        EXPECT_GT(floorPixels, 32 * 32 / 2);
        // Without the method's term the constant ambient (0 here) is all there is: black floor.
        s.gi = "none";
        const ImageF dark = renderHdr(scene, s);
        EXPECT_EQ(dark.at(16, 16)[0], 0.0f);
    }
}

TEST(Methods, EveryParameterRowRoundTripsAndValidates) {
    for (const GiMethod& m : giMethods())
        for (const ParamDesc& d : m.params) {
            const std::string key = m.name + "." + d.key;
            // A value that is not the default, written as text (the CLI), into settings, to JSON
            // (the settings file) and back.
            ParamValue other = d.defaultValue;
            switch (d.type) {
                case ParamType::Int:
                case ParamType::Float: other.number = d.defaultValue.number == d.max ? d.min : d.max; break;
                case ParamType::Bool: other.number = 1 - d.defaultValue.number; break;
                case ParamType::Choice: other.text = d.choices.back() == d.defaultValue.text ? d.choices.front() : d.choices.back(); break;
                case ParamType::Colour: other.colour = glm::vec3(float(d.max)); break;
            }
            RenderSettings s;
            setParam(s, key, formatParamValue(d, other));
            EXPECT_EQ(getParam(s, key), other) << key;
            const nlohmann::json j = nlohmann::json::parse(view::paramsToJson(s.params).dump());
            EXPECT_EQ(view::paramFromJson(key, j.at(key)), other) << key;
            // Out of range: one line naming the key and the range.
            std::string bad;
            if (d.type == ParamType::Int || d.type == ParamType::Float) bad = std::to_string(d.max * 2 + 1);
            else if (d.type == ParamType::Bool) bad = "maybe";
            else if (d.type == ParamType::Choice) bad = "no-such-choice";
            else bad = "-1";
            try {
                setParam(s, key, bad);
                ADD_FAILURE() << key << " accepted " << bad;
            } catch (const Error& e) {
                const std::string msg = e.what();
                EXPECT_EQ(msg.rfind(key + ": '", 0), 0u) << msg;
                EXPECT_NE(msg.find(describeParamRange(d)), std::string::npos) << msg;
                EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
            }
        }
    RenderSettings s;
    EXPECT_THROW(setParam(s, "ssao.frobnicate", "1"), Error);
    EXPECT_THROW(setParam(s, "nomethod.samples", "1"), Error);
    setParam(s, "--ao-radius", "0.5");  // an alias sets every row that declares it
    EXPECT_EQ(getParam(s, "ssao.radius").number, 0.5);
    EXPECT_EQ(getParam(s, "ao-reference.radius").number, 0.5);
}

TEST(Methods, LiveParametersNeverRebuildRebuildParametersDo) {
    registerConstantMethod();
    context();
    const Scene scene = floorScene(glm::vec3(0.5f));
    view::ViewSession session;
    view::ViewState state;
    ASSERT_TRUE(session.openScene(state, "builtin:cornell"));
    view::applyPanelAction(state, view::PanelAction::method(0, "test-constant"));
    session.renderFrame(state, 24, 24);
    const int built = session.rebuilds();
    const int made = constructions;
    view::applyPanelAction(state, view::PanelAction::param(0, "test-constant.radiance", "0,0,1"));
    session.renderFrame(state, 24, 24);
    EXPECT_EQ(session.rebuilds(), built) << "a live parameter rebuilt the renderer";
    EXPECT_EQ(constructions, made);
    view::applyPanelAction(state, view::PanelAction::param(0, "test-constant.divisor", "2"));
    session.renderFrame(state, 24, 24);
    EXPECT_EQ(session.rebuilds(), built + 1) << "a rebuild parameter must rebuild";
    EXPECT_EQ(constructions, made + 1);
    // The same for a built-in: SSAO's steps are live, its direction count is baked into a kernel.
    view::applyPanelAction(state, view::PanelAction::method(0, "ssao"));
    session.renderFrame(state, 24, 24);
    const int ssaoBuilt = session.rebuilds();
    view::applyPanelAction(state, view::PanelAction::param(0, "ssao.steps", "7"));
    session.renderFrame(state, 24, 24);
    EXPECT_EQ(session.rebuilds(), ssaoBuilt);
    view::applyPanelAction(state, view::PanelAction::param(0, "ssao.samples", "32"));
    session.renderFrame(state, 24, 24);
    EXPECT_EQ(session.rebuilds(), ssaoBuilt + 1);
}

TEST(Methods, CameraMovesKeepViewIndependentWork) {
    context();
    const Scene scene = makeBuiltinScene("cornell");
    RenderSettings s;
    s.width = s.height = 24;
    Renderer r(scene, s);
    r.renderFrame();
    const Pass& shadows = *r.passes().front();
    ASSERT_STREQ(shadows.name(), "shadows");
    EXPECT_FALSE(shadows.reusedLastFrame()) << "the first frame renders the maps";
    CameraMatrices moved = r.camera();
    moved.position += glm::vec3(0.1f, 0.0f, 0.0f);
    moved.view = glm::translate(moved.view, glm::vec3(-0.1f, 0.0f, 0.0f));
    moved.viewProj = moved.proj * moved.view;
    moved.invViewProj = glm::inverse(moved.viewProj);
    r.setCamera(moved);
    r.renderFrame();
    // Skipped as settled (renderer.h) or executed on its cache: not rendered again either way.
    EXPECT_TRUE(r.skippedLastFrame().front() || shadows.reusedLastFrame()) << "a camera move re-rendered the shadow maps";
    r.invalidate(ChangeLights);
    r.renderFrame();
    EXPECT_FALSE(shadows.reusedLastFrame()) << "a light change must re-render them";
}

TEST(Methods, ALightEditKeepsTheRendererAndRestartsTheProgressivePass) {
    context();
    view::ViewSession session;
    view::ViewState state;
    ASSERT_TRUE(session.openScene(state, "builtin:cornell"));
    view::applyPanelAction(state, view::PanelAction::method(0, "pathtrace"));
    for (int i = 0; i < 3; ++i) session.renderFrame(state, 16, 16);
    const int built = session.rebuilds();
    EXPECT_EQ(session.pane(0).renderer->samplesDone(), 3);
    view::PanelAction edit;
    edit.kind = view::PanelAction::SetLightIntensity;
    edit.index = 0;
    edit.value = 2.0f * state.lights[0].light.intensity;
    view::applyPanelAction(state, edit);
    session.renderFrame(state, 16, 16);
    EXPECT_EQ(session.rebuilds(), built) << "editing a light destroyed the renderer";
    EXPECT_EQ(session.pane(0).renderer->samplesDone(), 1) << "the path tracer did not restart";
}

// A pass that reads a frame resource it did not declare, or writes one it does not output.
class UndeclaredAccessPass final : public Pass {
public:
    UndeclaredAccessPass(bool write, gl::MemoryLedger& ledger) : write_(write) {
        texture_ = gl::createTexture2D({&ledger, name()}, GL_RGBA16F, 4, 4);
    }
    const char* name() const override { return "test-undeclared"; }
    std::vector<std::string> inputs() const override { return {resource::kGbufferDepth}; }
    std::vector<std::string> outputs() const override { return {resource::kIndirectDiffuse}; }
    void execute(Frame& frame) override {
        if (write_) frame.put(resource::kIndirectSpecular, texture_);
        else frame.texture(resource::kGbufferNormal);  // produced by the G-buffer, but not declared
        frame.put(resource::kIndirectDiffuse, texture_);
    }

private:
    bool write_;
    gl::Texture texture_;
};

TEST(Methods, AnUndeclaredReadOrWriteNamesThePassAndTheResource) {
    context();
    for (bool write : {false, true}) {
        const std::string name = write ? "test-undeclared-write" : "test-undeclared-read";
        if (!findGiMethod(name)) {
            GiMethod m;
            m.name = name;
            for (const std::string& p : presetNames()) m.presets.push_back({p, "", {}});
            m.addPasses = [write](MethodBuild& b) { b.add(std::make_unique<UndeclaredAccessPass>(write, b.ledger)); };
            registerGiMethod(m);
        }
        RenderSettings s;
        s.width = s.height = 8;
        s.gi = name;
        const Scene scene = makeBuiltinScene("cornell");
        Renderer r(scene, s);
        try {
            r.renderFrame();
            ADD_FAILURE() << name << ": an undeclared access was allowed";
        } catch (const Error& e) {
            const std::string what = e.what();
            EXPECT_NE(what.find("test-undeclared"), std::string::npos) << what;
            EXPECT_NE(what.find(write ? "indirect.specular" : "gbuffer.normal"), std::string::npos) << what;
        }
    }
}

// Every shader gets every module's uniform table as #defines, and the SDF and probe shaders use
// several tables at once: no two rows may share a name or a location (arrays take one per element).
TEST(Shaders, UniformTablesShareNoNameAndNoLocation) {
    std::map<int, std::string> owner;
    std::set<std::string> names;
    for (const gl::UniformSlot& u : uniformSlots()) {
        EXPECT_TRUE(names.insert(u.name).second) << u.name << " is declared twice";
        ASSERT_GE(u.count, 1) << u.name;
        EXPECT_LE(u.location + u.count, 1024) << u.name << ": past the 1024 locations GL 4.3 guarantees";
        for (int l = u.location; l < u.location + u.count; ++l) {
            auto [it, fresh] = owner.emplace(l, u.name);
            EXPECT_TRUE(fresh) << u.name << " and " << it->second << " both use location " << l;
        }
    }
    // What the shaders are compiled with: each row as a #define of its location.
    std::map<std::string, std::string> defines(sharedShaderDefines().begin(), sharedShaderDefines().end());
    for (const gl::UniformSlot& u : uniformSlots()) EXPECT_EQ(defines[u.name], std::to_string(u.location)) << u.name;
    EXPECT_EQ(defines["U_AO_KERNEL"], std::to_string(U_AO_KERNEL));
}

// Every uniform block, compiled from the declaration the shaders get, is laid out by GL exactly as
// its C++ struct: the same binding, each member at its offsetof, no larger than sizeof. Bindings are
// unique and leave 0 to the lights' block (shaders/lights.glsl).
TEST(Shaders, UniformBlocksAreLaidOutAsTheirCppStructs) {
    context();
    std::string preamble = "#version 450 core\n";
    for (const auto& [name, value] : sharedShaderDefines()) preamble += "#define " + name + " " + value + "\n";
    std::set<int> bindings{kLightsBinding};
    ASSERT_FALSE(uniformBlocks().empty());
    for (const gl::UniformBlockDesc& b : uniformBlocks()) {
        EXPECT_TRUE(bindings.insert(b.binding).second) << b.name << ": binding " << b.binding << " is taken";
        const gl::UniformBlockDesc::Member& first = b.members.front();
        const std::string touch = std::string("u_block.") + first.name + (first.count > 0 ? "[0]" : "") +
                                  (std::string(first.type) == "mat4" ? "[0][0]" : std::string(first.type).find("vec") != std::string::npos ? ".x" : "");
        const std::string source = preamble + "layout(local_size_x = 1) in;\n" + b.name + " u_block;\n" +
                                   "layout(std430, binding = 0) buffer Out { float o[]; };\n" +
                                   "void main() { o[0] = float(" + touch + "); }\n";
        const char* text = source.c_str();
        gl::Object program(glCreateShaderProgramv(GL_COMPUTE_SHADER, 1, &text), [](GLuint id) { glDeleteProgram(id); });
        GLint linked = 0;
        glGetProgramiv(program.id(), GL_LINK_STATUS, &linked);
        char log[2048] = {};
        glGetProgramInfoLog(program.id(), sizeof(log), nullptr, log);
        ASSERT_TRUE(linked) << b.name << ": " << log << "\n" << source;
        const GLuint block = glGetProgramResourceIndex(program.id(), GL_UNIFORM_BLOCK, b.name);
        ASSERT_NE(block, GL_INVALID_INDEX) << b.name;
        const GLenum blockProps[2] = {GL_BUFFER_BINDING, GL_BUFFER_DATA_SIZE};
        GLint blockValues[2] = {};
        glGetProgramResourceiv(program.id(), GL_UNIFORM_BLOCK, block, 2, blockProps, 2, nullptr, blockValues);
        EXPECT_EQ(blockValues[0], b.binding) << b.name;
        EXPECT_LE(size_t(blockValues[1]), b.size) << b.name << ": GL's block is larger than the C++ struct";
        for (const gl::UniformBlockDesc::Member& m : b.members) {
            const std::string member = std::string(b.name) + "." + m.name + (m.count > 0 ? "[0]" : "");
            const GLuint index = glGetProgramResourceIndex(program.id(), GL_UNIFORM, member.c_str());
            ASSERT_NE(index, GL_INVALID_INDEX) << member;
            const GLenum offsetProp = GL_OFFSET;
            GLint offset = -1;
            glGetProgramResourceiv(program.id(), GL_UNIFORM, index, 1, &offsetProp, 1, nullptr, &offset);
            EXPECT_EQ(size_t(offset), m.offset) << member << ": GLSL and C++ disagree on its offset";
        }
    }
}

TEST(Methods, DuplicateOutputsAreRefusedAtConstruction) {
    context();
    if (!findGiMethod("test-duplicate")) {
        GiMethod m;
        m.name = "test-duplicate";
        for (const std::string& p : presetNames()) m.presets.push_back({p, "", {}});
        m.addPasses = [](MethodBuild& b) {
            b.add(std::make_unique<ConstantIndirectPass>(b.settings, b.ledger));
            b.add(std::make_unique<ConstantIndirectPass>(b.settings, b.ledger));
        };
        registerGiMethod(m);
        registerConstantMethod();
    }
    RenderSettings s;
    s.width = s.height = 8;
    s.gi = "test-duplicate";
    try {
        Renderer r(makeBuiltinScene("cornell"), s);
        ADD_FAILURE() << "two writers of one name were accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("indirect.diffuse"), std::string::npos) << e.what();
    }
}

TEST(Methods, StepTimersAndFrameResourcesCarryTheirShape) {
    registerConstantMethod();
    context();
    RenderSettings s;
    s.width = 20;
    s.height = 10;
    s.gi = "test-constant";
    setParam(s, "test-constant.divisor", "2");
    Renderer r(makeBuiltinScene("cornell"), s);
    for (int i = 0; i < 3; ++i) r.renderFrame();
    const FrameResource& indirect = r.frameResources().at("indirect.diffuse");
    EXPECT_EQ(indirect.kind, ResourceKind::Texture2D);
    EXPECT_EQ(indirect.width, 10);
    EXPECT_EQ(indirect.height, 5);
    EXPECT_EQ(indirect.format, GLenum(GL_RGBA32F));
    EXPECT_EQ(r.frameResources().at("lights").kind, ResourceKind::Buffer);
    EXPECT_EQ(r.frameResources().at("shadow.cubes").kind, ResourceKind::Texture2DArray);  // the cube faces as layers
    bool stepSeen = false;
    for (const PassTiming& t : r.timings(1))
        if (t.pass == "test-constant/fill") {
            stepSeen = true;
            EXPECT_TRUE(t.step);
            EXPECT_EQ(t.workedFrames, 3);
        }
    EXPECT_TRUE(stepSeen);
}

// Debug views: listed, refused when a method does not produce them, G-buffer views in every method.
TEST(Methods, DebugViewsAreListedAndTheGBufferWorksInEveryMethod) {
    const CliResult list = runCli("render --scene builtin:cornell --gi ssao --view list");
    EXPECT_EQ(list.status, 0) << list.err;
    for (const char* v : {"final", "ao", "gbuffer.normal", "gbuffer.depth"})
        EXPECT_NE(list.out.find(v), std::string::npos) << v << "\n" << list.out;
    const std::string dir = tempDir("debug_views");
    // The path tracer lights no G-buffer, so has no lighting terms ("ao" among them).
    const CliResult noAo = runCli("render --scene builtin:cornell --gi pathtrace --view ao --out " + dir + "/x.png");
    EXPECT_NE(noAo.status, 0);
    EXPECT_NE(noAo.err.find("is not produced by --gi pathtrace"), std::string::npos) << noAo.err;
    EXPECT_FALSE(fileExists(dir + "/x.png"));
    const CliResult normals = runCli("render --scene builtin:cornell --size 32x32 --gi pathtrace --spp 1 --view "
                                     "gbuffer.normal --out " + dir + "/n.png");
    EXPECT_EQ(normals.status, 0) << normals.err;
    const ImageU8 n = readPng(dir + "/n.png");
    // The floor's normal (0, 1, 0) shows as (128, 255, 128).
    const uint8_t* floor = &n.rgba[(size_t(30) * 32 + 16) * 4];
    EXPECT_NEAR(floor[0], 128, 2);
    EXPECT_NEAR(floor[1], 255, 2);
    EXPECT_NEAR(floor[2], 128, 2);
}

// --timings is honest for progressive methods: the median frame, the total and per sample, and
// "cached" only when nothing ran; the total line sums per-frame medians (a frame's cost), not the
// samples' totals.
TEST(Methods, ProgressiveTimingsReportTotalAndPerSample) {
    const std::string dir = tempDir("timings");
    const CliResult r = runCli("render --scene builtin:cornell --size 16x16 --gi pathtrace --spp 16 --timings "
                               "--frames 6 --warmup 1 --out " + dir + "/pt.png");
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("for 16 samples"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("ms/sample"), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("pathtrace  (cached"), std::string::npos) << r.out;
    std::istringstream lines(r.out);
    double median = -1.0, total = -1.0, samplesTotal = -1.0;
    for (std::string line; std::getline(lines, line);) {
        std::istringstream words(line);
        std::string name;
        words >> name;
        if (name == "pathtrace") words >> median, std::sscanf(line.c_str() + line.find("total"), "total %lf", &samplesTotal);
        if (name == "total") words >> total;
    }
    EXPECT_GT(median, 0.0) << "the pass's median frame is printed\n" << r.out;
    EXPECT_LT(total, samplesTotal) << "the total line is a frame's cost\n" << r.out;
}

}  // namespace
}  // namespace gis::test

namespace gis::test {
namespace {

// What a method built is reported where memory is: `info --gi`, --timings (and the panel).
TEST(Methods, VolumesAndProbesAreReportedInWorldUnits) {
    const CliResult info = runCli("info --scene builtin:cornell --size 32x32 --gi probes --preset low");
    ASSERT_EQ(info.status, 0) << info.err;
    EXPECT_NE(info.out.find("bytes per probe"), std::string::npos) << info.out;
    EXPECT_NE(info.out.find("world units"), std::string::npos) << info.out;
    const std::string dir = tempDir("method_stats");
    const CliResult timings = runCli("render --scene builtin:cornell --size 16x16 --gi vct --preset low --timings "
                                     "--frames 2 --warmup 0 --out " + dir + "/v.png");
    ASSERT_EQ(timings.status, 0) << timings.err;
    EXPECT_NE(timings.out.find("32^3 voxels of"), std::string::npos) << timings.out;
}

}  // namespace
}  // namespace gis::test
