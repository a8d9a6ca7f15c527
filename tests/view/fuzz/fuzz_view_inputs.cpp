// libFuzzer target for the viewer's text inputs: settings files (JSON) and view scripts. The first
// byte picks the input (even: settings, odd: script), the rest is the file's text. Findings are a
// crash, a sanitizer report, or a broken promise checked here:
//   - bad input is a gis::Error (never another exception escaping the parser);
//   - a settings file that loads saves and loads again, to the same JSON (what save-settings
//     writes always loads).
// Built by build_fuzzer.sh (clang++, ASan + UBSan on these sources) against the project's libraries.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include <nlohmann/json.hpp>

#include "scene/scene.h"
#include "cli/settings_io.h"
#include "view/view_script.h"

namespace {

void settings(const std::string& text) {
    const nlohmann::json j = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
    if (j.is_discarded()) return;
    gis::view::ViewState s;
    try {
        gis::view::viewStateFromJson(j, s);
    } catch (const gis::Error&) {
        return;  // refused with a message: the expected outcome for most inputs
    }
    const std::string saved = gis::view::viewStateToJson(s).dump();
    gis::view::ViewState again;
    try {
        gis::view::viewStateFromJson(nlohmann::json::parse(saved), again);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "a loaded state does not load again: %s\nsaved: %s\n", e.what(), saved.c_str());
        std::abort();
    }
    if (gis::view::viewStateToJson(again).dump() != saved) {
        std::fprintf(stderr, "a loaded state changes when saved and loaded again:\n%s\n%s\n", saved.c_str(),
                     gis::view::viewStateToJson(again).dump().c_str());
        std::abort();
    }
}

void script(const std::string& text) {
    try {
        gis::view::parseScript(text, "fuzz.txt");
    } catch (const gis::Error&) {
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size == 0) return 0;
    const std::string text(reinterpret_cast<const char*>(data) + 1, size - 1);
    if (data[0] % 2 == 0) settings(text);
    else script(text);
    return 0;
}
