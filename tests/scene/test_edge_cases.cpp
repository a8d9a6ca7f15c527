// Every .gltf/.glb under shared/assets/gltf/_edge_cases/ (found at test time, recursively) either
// loads or throws gis::Error with a non-empty one-line message naming the file, then the problem
// in at most 200 characters. The expected
// outcome of each file is the documented acceptance table edge_case_outcomes.txt next to this
// source; a changed outcome (or a file missing from the table) fails the test.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "test_util.h"

using namespace gistest;
namespace fs = std::filesystem;

#ifndef GIS_EDGE_CASE_TABLE
#error "GIS_EDGE_CASE_TABLE must point to edge_case_outcomes.txt"
#endif

namespace {

std::map<std::string, std::string> readTable() {
    std::map<std::string, std::string> table;
    std::ifstream f(GIS_EDGE_CASE_TABLE);
    std::string line;
    while (std::getline(f, line)) {
        if (line.empty() || line[0] == '#') continue;
        std::istringstream in(line);
        std::string outcome, path;
        in >> outcome;
        std::getline(in, path);
        path.erase(0, path.find_first_not_of(' '));
        if (!path.empty()) table[path] = outcome;
    }
    return table;
}

}  // namespace

TEST(EdgeCases, EachLoadsOrFailsCleanlyAsDocumented) {
    const fs::path root = fs::path(gltfDir()) / "_edge_cases";
    ASSERT_TRUE(fs::is_directory(root)) << root;
    std::vector<std::string> files;
    for (const auto& e : fs::recursive_directory_iterator(root)) {
        const std::string ext = e.path().extension().string();
        if (e.is_regular_file() && (ext == ".gltf" || ext == ".glb"))
            files.push_back(fs::relative(e.path(), root).string());
    }
    std::sort(files.begin(), files.end());
    ASSERT_GT(files.size(), 0u);
    ASSERT_TRUE(std::ifstream(GIS_EDGE_CASE_TABLE).good()) << "cannot read " << GIS_EDGE_CASE_TABLE;
    const std::map<std::string, std::string> table = readTable();

    size_t loads = 0, errors = 0, changed = 0;
    std::ostringstream report;
    for (const std::string& rel : files) {
        const std::string path = (root / rel).string();
        std::string outcome, message;
        try {
            const gis::Scene s = gis::loadGltfFile(path);
            outcome = "load";
            message = std::to_string(s.triangleCount()) + " triangles, " +
                      std::to_string(s.warnings.size()) + " warnings";
            ++loads;
        } catch (const gis::Error& e) {
            outcome = "error";
            message = e.what();
            ++errors;
            EXPECT_FALSE(message.empty()) << rel;
            EXPECT_EQ(message.find('\n'), std::string::npos) << rel;
            EXPECT_EQ(message.rfind(path + ": ", 0), 0u) << "message does not name the file: " << message;
            EXPECT_GT(message.size(), path.size() + 2) << rel;
            message = message.substr(std::min(message.size(), path.size() + 2));
            // The problem itself: short, and never one of tinygltf's texts that name nothing
            // ("File not found :" without the file, "tinygltf failed", "JSON string too short").
            EXPECT_LE(message.size(), 200u) << rel << ": " << message;
            for (const char* vague : {"tinygltf failed", "JSON string too short", "[json.exception"})
                EXPECT_EQ(message.find(vague), std::string::npos) << rel << ": " << message;
            const size_t nf = message.find("File not found :");
            EXPECT_TRUE(nf == std::string::npos || message.find_first_not_of(' ', nf + 16) != std::string::npos)
                << rel << ": names no file: " << message;
        }
        // Any other exception type escapes and fails the test (as would a crash).
        auto it = table.find(rel);
        const std::string expected = it == table.end() ? "(missing)" : it->second;
        const bool ok = expected == outcome;
        changed += !ok;
        report << (ok ? "  " : "! ") << outcome << (outcome == "load" ? "  " : " ") << rel << " | " << message
               << (ok ? "" : "   [expected " + expected + "]") << "\n";
        EXPECT_EQ(outcome, expected) << rel << ": " << message;
    }
    std::printf("Edge cases (%zu files: %zu load, %zu error, %zu changed):\n%s", files.size(), loads,
                errors, changed, report.str().c_str());
}
