// Runs the gisandbox executable as a user would and captures what it prints.
#pragma once

#include <string>

namespace gis::test {

struct CliResult {
    int status = -1;      // exit status
    std::string out, err;
};

// `args` is appended to the executable path as-is (shell quoting is the caller's business);
// `env` is prefixed (e.g. "GIS_SHADER_DIR=/tmp/x").
CliResult runCli(const std::string& args, const std::string& env = "");
std::string tempDir(const std::string& name);  // fresh, empty directory under the build tree
bool fileExists(const std::string& path);
int countLines(const std::string& text);

}  // namespace gis::test
