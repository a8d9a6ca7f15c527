#include "cli_util.h"

#include <sys/wait.h>

#include <filesystem>
#include <fstream>
#include <sstream>

namespace gis::test {

namespace {
std::string slurp(const std::string& path) {
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}
}  // namespace

std::string tempDir(const std::string& name) {
    namespace fs = std::filesystem;
    fs::path dir = fs::path(GIS_TEST_TMP) / name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir.string();
}

CliResult runCli(const std::string& args, const std::string& env) {
    static int counter = 0;
    std::filesystem::create_directories(GIS_TEST_TMP);
    const std::string base = std::string(GIS_TEST_TMP) + "/cli" + std::to_string(::getpid()) + "_" + std::to_string(counter++);
    const std::string cmd = env + (env.empty() ? "" : " ") + "'" + GIS_BINARY + "' " + args + " >'" + base +
                            ".out' 2>'" + base + ".err' </dev/null";
    const int raw = std::system(cmd.c_str());
    CliResult r;
    r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : 128 + WTERMSIG(raw);
    r.out = slurp(base + ".out");
    r.err = slurp(base + ".err");
    std::filesystem::remove(base + ".out");
    std::filesystem::remove(base + ".err");
    return r;
}

bool fileExists(const std::string& path) { return std::filesystem::exists(path); }

int countLines(const std::string& text) {
    int n = 0;
    for (char c : text) n += c == '\n';
    if (!text.empty() && text.back() != '\n') ++n;
    return n;
}

}  // namespace gis::test
