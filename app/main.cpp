// gisandbox command line: render, info, shaders. Every failure ends with one line on stderr
// ("gisandbox: error: ...") and a non-zero exit status.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstdio>
#include <functional>
#include <memory>
#include <new>

#include "cli/commands.h"
#include "scene/atomic_file.h"
#include "scene/scene.h"
#include "scene/scene_lighting.h"

namespace {

// CLI11 names unexpected arguments last first ("vct --gii"): say them in the order typed, and
// offer the command's nearest option for a mistyped flag.
std::string extrasMessage(const CLI::App& app, int argc, char** argv) {
    std::vector<std::string> extras = app.remaining(true), typed;
    for (int i = 1; i < argc; ++i) {
        const auto it = std::find(extras.begin(), extras.end(), argv[i]);
        if (it != extras.end()) typed.push_back(*it), extras.erase(it);
    }
    typed.insert(typed.end(), extras.begin(), extras.end());
    std::string list, hint;
    for (const std::string& a : typed) list += (list.empty() ? "" : " ") + a;
    const CLI::App* cmd = app.get_subcommands().empty() ? &app : app.get_subcommands().back();
    std::vector<std::string> flags;
    for (const CLI::Option* opt : cmd->get_options())
        for (const std::string& name : opt->get_lnames()) flags.push_back("--" + name);
    for (const std::string& a : typed)
        if (a.rfind("--", 0) == 0 && hint.empty()) hint = gis::didYouMean(a.substr(0, a.find('=')), flags);
    if (!hint.empty()) hint = " (" + hint.substr(0, hint.size() - 1) + ")";
    // "--set vct.resolution 64": the value went in as a word of its own.
    for (int i = 2; i < argc && hint.empty(); ++i)
        if (std::string(argv[i - 1]) == "--set" && std::string(argv[i]).find('=') == std::string::npos &&
            i + 1 < argc && std::find(typed.begin(), typed.end(), argv[i + 1]) != typed.end())
            hint = std::string(" (--set takes METHOD.KEY=VALUE: --set ") + argv[i] + "=" + argv[i + 1] + ")";
    return "unexpected argument" + std::string(typed.size() == 1 ? "" : "s") + ": " + list + hint;
}

std::string parseErrorMessage(CLI::App& app, const CLI::ParseError& e, int argc, char** argv) {
    std::string what = dynamic_cast<const CLI::ExtrasError*>(&e) ? extrasMessage(app, argc, argv) : e.what();
    // A word where a command belongs: name it and the commands there are.
    bool known = false;
    std::string names;
    for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; })) {
        known = known || (argc > 1 && sub->get_name() == argv[1]);
        names += (names.empty() ? "" : ", ") + sub->get_name();
    }
    std::vector<std::string> commands;
    for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; })) commands.push_back(sub->get_name());
    if (argc > 1 && argv[1][0] != '-' && !known)
        what = std::string("unknown command '") + argv[1] + "' (" + gis::didYouMean(argv[1], commands) + "expected " +
               names + ")";
    return what;
}

// A subcommand: its name, its help line, and `attach`, which adds its options to the parsed
// command and returns what runs it with them.
struct Subcommand {
    const char* name;
    const char* help;
    std::function<std::function<int()>(CLI::App&)> attach;
};

template <class Options>
Subcommand subcommand(const char* name, const char* help, void (*addOptions)(CLI::App&, Options&),
                      int (*run)(const Options&)) {
    return {name, help, [addOptions, run](CLI::App& cmd) -> std::function<int()> {
                auto options = std::make_shared<Options>();
                addOptions(cmd, *options);
                return [options, run] { return run(*options); };
            }};
}

}  // namespace

int main(int argc, char** argv) {
    // A file-size limit (ulimit -f) makes a write fail with EFBIG, reported like any other write
    // error, instead of killing the process with a partial file.
    gis::ignoreFileSizeSignal();
    CLI::App app{"gisandbox: explore and compare real-time global illumination against a reference"};
    app.require_subcommand(1);
    app.set_version_flag("--version", "gisandbox " GIS_VERSION);
    app.set_help_all_flag("--help-all", "Show help for every subcommand");
    // Usage errors are one line too, like every other failure.
    app.failure_message([](const CLI::App*, const CLI::Error& e) {
        return std::string("gisandbox: error: ") + e.what() + " (see --help)\n";
    });

    // The subcommands in the order --help lists them; each is declared once here.
    const Subcommand subcommands[] = {
        subcommand("render", "Render a scene headless (or in a hidden window) to PNG or EXR", gis::addRenderOptions,
                   gis::runRender),
        subcommand("info", "Print a scene's meshes, triangles, materials, lights, bounds and GPU memory",
                   gis::addInfoOptions, gis::runInfo),
        subcommand("methods", "List the GI methods, or one method's parameters and presets", gis::addMethodsOptions,
                   gis::runMethods),
        subcommand("export", "Write a scene (e.g. a built-in one) as glTF for other renderers", gis::addExportOptions,
                   gis::runExport),
        subcommand("shaders", "Write every shader program the app can request, preprocessed", gis::addShaderDumpOptions,
                   gis::runShaderDump),
        subcommand("bench", "Measure every GI method and preset: GPU ms, memory, error vs a path-traced reference",
                   gis::addBenchOptions, gis::runBench),
        subcommand("view", "Open the interactive sandbox: a window with the GI methods side by side and a panel",
                   gis::addViewOptions, gis::runView),
        subcommand("diff", "Compare an image with a reference: RMSE, relMSE, PSNR, SSIM, FLIP", gis::addDiffOptions,
                   gis::runDiff),
    };
    std::vector<std::pair<const CLI::App*, std::function<int()>>> runs;
    for (const Subcommand& c : subcommands) {
        CLI::App* cmd = app.add_subcommand(c.name, c.help);
        runs.emplace_back(cmd, c.attach(*cmd));
    }

    // Exit status: 0 success (and --help, --version), 1 any failure, usage errors included.
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForVersion& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::fprintf(stderr, "gisandbox: error: %s (see --help)\n", parseErrorMessage(app, e, argc, argv).c_str());
        return 1;
    }
    try {
        for (const auto& [cmd, run] : runs)
            if (cmd->parsed()) return run();
    } catch (const gis::Error& e) {
        std::fprintf(stderr, "gisandbox: error: %s\n", e.what());
        return 1;
    } catch (const std::bad_alloc&) {
        std::fprintf(stderr, "gisandbox: error: out of memory\n");
        return 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "gisandbox: error: %s\n", e.what());
        return 1;
    }
    return 1;
}
