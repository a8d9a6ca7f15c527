// Helpers shared by the scene sources (not part of the public contract in scene.h).
#pragma once

#include <map>
#include <string>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

namespace gis::detail {

// Makes `s` safe for a one-line message: control characters become spaces, runs of spaces
// collapse, and anything past `maxLen` characters is cut with "...".
std::string oneLine(const std::string& s, size_t maxLen = 400);

// glTF node transform T * R * S (rotation normalised; a zero quaternion counts as identity).
glm::mat4 composeTrs(const glm::dvec3& t, const glm::dquat& r, const glm::dvec3& s);

bool isFinite(const glm::mat4& m);

}  // namespace gis::detail

namespace gis {
struct Scene;
}

namespace gis::detail {

// Options of a built-in scene: builtin:NAME?key=value&key=value.
using SceneOptions = std::map<std::string, double>;
SceneOptions parseSceneOptions(const std::string& spec, const std::string& query);
// The GI test scenes (renderer/scene/builtin_gi_scenes.cpp).
Scene makeLeakScene(const SceneOptions& options);
Scene makeRoomScene(const SceneOptions& options);
Scene makeMirrorScene(const SceneOptions& options);
Scene makeAtriumScene(const SceneOptions& options);
Scene makeBuildingScene(const SceneOptions& options);

}  // namespace gis::detail
