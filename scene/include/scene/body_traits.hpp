#pragma once
// What the stages need to know about a body kind, answered in one place.
// Every switch over BodyKind here has no default: a new kind does not
// compile until each question has its answer.
#include <optional>
#include <string>

#include "scene/scene.hpp"

namespace scene {

// Weak-branch shock angle (radians) when the scene's body carries an
// attached oblique shock with an exact inviscid solution (a wedge within its
// maximum deflection); nullopt otherwise.
std::optional<double> attached_shock_beta(const Scene& s);
// The same for a body in a stream of the given Mach number and gamma (the
// granular gas has its own).
std::optional<double> attached_shock_beta(const BodySpec& b, double mach, double gamma);
// True when the exact inviscid reference of the scene's flow is the uniform
// state behind an attached oblique shock (so the whole field is known).
bool reference_is_exact_oblique_shock(const Scene& s);
// True when the scene's shock may stand off the body, ahead of its nose on
// the stagnation line (the symmetry line y = make_body(...).nose.y): every
// body without an attached oblique shock (discs, Apollo, polygons, whose
// nose may be blunt, and wedges beyond their maximum deflection). A polygon
// whose pointed nose carries an attached shock has none ahead of the nose.
bool shock_may_stand_off(const Scene& s);

// Face length, in scene units, when the body is a single straight ramp from
// the origin at angle_deg (the wall on which an inviscid flow has a uniform
// pressure, and the geometry of the block-structured wedge grid); nullopt
// for other bodies.
std::optional<double> straight_ramp_length(const BodySpec& b);

// Deflection angle (degrees) the restitution calibration is indexed by: the
// table is calibrated on wedges against their exact shock angle. nullopt
// for bodies it was not calibrated on (they take it by Mach number alone).
std::optional<double> calibration_angle_deg(const BodySpec& b);

// The shape class a blunt body's own restitution fit is indexed by (the
// calibration table's bow_shock.shapes): bodies of one kind share their
// nose's form, so their granular bow shocks share one e(M). nullopt for
// wedges (the wedge fit is theirs) and polygons (no two need share a form).
std::optional<std::string> bow_shape_class(const BodySpec& b);

// Radius a bow-shock correlation (Billig's cylinder) is evaluated with, in
// scene units: the disc's radius; for other bodies, half the body's frontal
// height (an approximation: their noses are not circular cylinders).
double correlation_nose_radius(const BodySpec& b);
// True when that radius is the body's own nose radius (no approximation).
bool correlation_is_exact_shape(const BodySpec& b);

// The band cells' along/across aspect meshgen lays the shock-aligned strips
// with: mesh.anisotropy where the scene sets it; otherwise
// kStraightShockAnisotropy for a body carrying an attached oblique shock
// (a straight shock, where cells that long resolve all it varies along it)
// and 1 (the isotropic band) for a bow shock, whose strips have not been
// measured through the pipeline.
inline constexpr double kStraightShockAnisotropy = 10.0;
double band_anisotropy(const Scene& s);

// Whether a flow past this body starts at rest rather than in the free
// stream (cfd.start auto, above the rest-start Mach limit). Wedges: no, an
// attached wedge's base lies on the outflow boundary, so an impulsive start
// has no afterbody to open a vacuum behind, and at rest the starting shock
// creeps in from the inlet (at Mach 2 it travels at 0.26 c); a detached
// wedge's base lies inside the domain (sharp_base_inside_domain), and the
// CFD stage starts its wake at rest behind the widest station. Other
// bodies: yes (Apollo's receding afterbody; discs and polygons as measured in
// the case studies).
bool starts_at_rest(const BodySpec& b);

// Estimated Mach number just behind the shock where it crosses the outflow
// station: the body's widest station (or the domain's outflow boundary, if
// upstream of it; meshgen ends a body's grid there). Attached wedges: the
// exact flow behind the oblique shock. Other bodies: Billig's cylinder shock
// (standoff and hyperbola, nose radius correlation_nose_radius) at that
// station, its local angle giving the oblique-shock state behind it. Below 1
// the outflow boundary cuts the subsonic region behind the bow shock, where
// an extrapolating (supersonic) outflow condition leaves the pressure
// undetermined.
double post_shock_mach_at_outflow(const Scene& s);
// True when the flow can leave the domain subsonic behind the shock: that
// Mach number is below 1, or the shock is detached ahead of a wedge, whose
// base corner (its widest station, where the sonic line begins) lies on the
// outflow boundary.
bool outflow_can_be_subsonic(const Scene& s);
// True when the body has a sharp base corner (a wedge's widest station)
// inside the domain, with wake behind it: the default domain of a wedge
// whose shock stands off, or a domain override reaching past the base.
bool sharp_base_inside_domain(const Scene& s);
// x of the body's widest station (a wedge's base plane), body lengths.
double widest_station_x(const Scene& s);

}  // namespace scene
