#pragma once
// What the stages need to know about a body kind, answered in one place.
// Every switch over BodyKind here has no default: a new kind does not
// compile until each question has its answer.
#include <optional>

#include "scene/scene.hpp"

namespace scene {

// Weak-branch shock angle (radians) when the scene's body carries an
// attached oblique shock with an exact inviscid solution (a wedge within its
// maximum deflection); nullopt otherwise.
std::optional<double> attached_shock_beta(const Scene& s);

// Radius a bow-shock correlation (Billig's cylinder) is evaluated with, in
// scene units: the disc's radius; for other bodies, half the body's frontal
// height (an approximation: their noses are not circular cylinders).
double correlation_nose_radius(const BodySpec& b);
// True when that radius is the body's own nose radius (no approximation).
bool correlation_is_exact_shape(const BodySpec& b);

}  // namespace scene
