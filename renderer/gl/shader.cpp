#include "gl/shader.h"

#include <fstream>
#include <regex>
#include <set>
#include <sstream>

#include "error.h"

namespace gis {

std::string shaderDir() {
    const char* env = std::getenv("GIS_SHADER_DIR");
    return env && *env ? env : GIS_SHADER_DIR;
}

namespace {

std::string readShaderFile(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error("cannot read shader " + path);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

void emit(PreprocessedShader& out, const std::string& text, const std::string& file, int line) {
    out.source += text + "\n";
    out.lines.push_back({file, line});
}

void expand(const std::string& name, PreprocessedShader& out, std::set<std::string>& included, int depth) {
    if (depth > 16) throw Error("shader include nesting too deep at " + name);
    const std::string path = shaderDir() + "/" + name;
    const std::string text = readShaderFile(path);
    const std::string file = "shaders/" + name;
    static const std::regex includeLine(R"(^\s*#\s*include\s+"([^"]+)\"\s*$)");
    static const std::regex versionLine(R"(^\s*#\s*version\b.*$)");
    std::istringstream lines(text);
    std::string line;
    int lineNo = 0;
    while (std::getline(lines, line)) {
        ++lineNo;
        std::smatch m;
        if (std::regex_match(line, m, includeLine)) {
            const std::string inc = m[1];
            if (included.insert(inc).second) expand(inc, out, included, depth + 1);
        } else if (std::regex_match(line, versionLine)) {
            emit(out, "", file, lineNo);  // the version line is emitted once, first, by preprocessShader
        } else {
            emit(out, line, file, lineNo);
        }
    }
}

}  // namespace

PreprocessedShader preprocessShader(const std::string& file,
                                    const std::vector<std::pair<std::string, std::string>>& defines) {
    PreprocessedShader out;
    emit(out, "#version 450 core", "(generated)", 0);
    for (const auto& [name, value] : sharedShaderDefines()) emit(out, "#define " + name + " " + value, "(generated)", 0);
    for (const auto& [name, value] : defines) emit(out, "#define " + name + " " + value, "(generated)", 0);
    std::set<std::string> included;
    expand(file, out, included, 0);
    return out;
}

std::string mapShaderLog(const std::string& log, const PreprocessedShader& shader) {
    static const std::regex mesa(R"(^\d+:(\d+)\(\d+\):\s*(.*)$)");
    static const std::regex nvidia(R"(^\d+\((\d+)\)\s*:\s*(.*)$)");
    std::istringstream lines(log);
    std::string line, out;
    while (std::getline(lines, line)) {
        std::smatch m;
        if (std::regex_match(line, m, mesa) || std::regex_match(line, m, nvidia)) {
            const size_t index = std::stoul(m[1]);
            if (index >= 1 && index <= shader.lines.size()) {
                const auto& origin = shader.lines[index - 1];
                line = origin.file + ":" + std::to_string(origin.line) + ": " + m[2].str();
            }
        }
        if (!line.empty()) out += line + "\n";
    }
    return out;
}

namespace {

GLenum stageOf(const std::string& file) {
    auto ends = [&](const char* ext) { return file.size() > 5 && file.compare(file.size() - 5, 5, ext) == 0; };
    if (ends(".vert")) return GL_VERTEX_SHADER;
    if (ends(".frag")) return GL_FRAGMENT_SHADER;
    if (ends(".geom")) return GL_GEOMETRY_SHADER;
    if (ends(".comp")) return GL_COMPUTE_SHADER;
    throw Error("shader " + file + ": unknown stage (expected .vert .geom .frag .comp)");
}

std::string firstLines(const std::string& text, int maxLines) {
    std::istringstream in(text);
    std::string line, out;
    int n = 0, total = 0;
    while (std::getline(in, line)) {
        if (line.empty()) continue;
        if (n < maxLines) { out += (n ? " | " : "") + line; ++n; }
        ++total;
    }
    if (total > n) out += " (+" + std::to_string(total - n) + " more lines)";
    return out;
}

void deleteProgram(GLuint id) { glDeleteProgram(id); }

}  // namespace

gl::Object buildProgram(const ProgramDesc& desc) {
    gl::Object program(glCreateProgram(), deleteProgram);
    std::vector<GLuint> shaders;
    auto cleanup = [&] { for (GLuint s : shaders) glDeleteShader(s); };
    try {
        for (const std::string& file : desc.stages) {
            PreprocessedShader pre = preprocessShader(file, desc.defines);
            GLuint shader = glCreateShader(stageOf(file));
            shaders.push_back(shader);
            const char* src = pre.source.c_str();
            glShaderSource(shader, 1, &src, nullptr);
            glCompileShader(shader);
            GLint ok = 0;
            glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
            if (!ok) {
                GLint len = 0;
                glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &len);
                std::string log(std::max(len, 1), '\0');
                glGetShaderInfoLog(shader, len, nullptr, log.data());
                throw Error("shader compile error in program '" + desc.name + "': " +
                            firstLines(mapShaderLog(log.c_str(), pre), 3));
            }
            glAttachShader(program.id(), shader);
        }
        glLinkProgram(program.id());
        GLint ok = 0;
        glGetProgramiv(program.id(), GL_LINK_STATUS, &ok);
        if (!ok) {
            GLint len = 0;
            glGetProgramiv(program.id(), GL_INFO_LOG_LENGTH, &len);
            std::string log(std::max(len, 1), '\0');
            glGetProgramInfoLog(program.id(), len, nullptr, log.data());
            throw Error("shader link error in program '" + desc.name + "': " + firstLines(log.c_str(), 3));
        }
    } catch (...) {
        cleanup();
        throw;
    }
    cleanup();
    return program;
}

}  // namespace gis
