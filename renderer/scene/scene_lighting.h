// Which scenes their own emission lights, for `--lighting auto` (renderer/scene/scene_setup.cpp),
// and the "did you mean" of the messages for a mistyped name (renderer/scene/suggest.cpp).
#pragma once

#include <string>
#include <vector>

#include "scene/scene.h"

namespace gis {

// Emission lights a scene (Cornell boxes, emitter-lit rooms) when its power is a real share of
// what reaches the surfaces; a model whose emission is a texture detail (DamagedHelmet's lamps and
// displays) is not lit by it, and `--lighting auto` gives it the default sun and sky. The measure
// is the area-weighted mean emitted luminance over every surface; the floor sits far from both
// kinds (docs/first-hour.md has the numbers).
double meanEmittedRadiance(const Scene& scene);
constexpr double kEmitterLightingFloor = 0.015;
bool emissionLightsScene(const Scene& scene);  // meanEmittedRadiance >= kEmitterLightingFloor

// Bounce feedback (a method that adds one bounce per update from its own last result: the probe
// field's replacing updates, vct.feedback) leaves albedo^n of the light out after n updates: the
// updates it takes for the scene's brightest diffuse albedo to leave under 1% out, at least 1 and
// at most kMaxFeedbackBounces (reached from albedo 0.93).
constexpr int kMaxFeedbackBounces = 64;
int feedbackBouncesFor(const Scene& scene);

// "did you mean 'X'? " for the candidate a typo of `given` most likely meant, or "" when none is
// close; messages put it before their list of what is available.
std::string didYouMean(const std::string& given, const std::vector<std::string>& candidates);

}  // namespace gis
