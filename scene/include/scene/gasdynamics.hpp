#pragma once
// Exact and correlated ideal-gas shock relations used as references
// (docs/units.md). Angles in radians unless a name says _deg.
#include <optional>

namespace scene {

// Weak-shock wave angle beta for deflection theta at Mach M (theta-beta-Mach
// relation); nullopt when theta exceeds the maximum deflection (detached).
std::optional<double> oblique_shock_beta(double mach, double theta, double gamma);
double max_deflection(double mach, double gamma);
// Static pressure ratio p2/p1 across an oblique shock of angle beta.
double oblique_pressure_ratio(double mach, double beta, double gamma);
// Density ratio rho2/rho1 across an oblique shock of angle beta.
double oblique_density_ratio(double mach, double beta, double gamma);
// Mach number behind an oblique shock of angle beta and deflection theta.
double oblique_downstream_mach(double mach, double beta, double theta, double gamma);
// Flow deflection theta behind an oblique shock of angle beta (either
// branch; 0 at the Mach angle and at a normal shock).
double oblique_deflection(double mach, double beta, double gamma);

// Lowest inflow Mach number at which a flow started at rest behind a
// supersonic inflow boundary stays inside the domain: the inflow (u = M)
// meeting gas at rest (u = 0, same p and T) is a symmetric Riemann problem
// whose two shocks each take half the velocity jump. The left one travels at
// M - Ms in the lab frame, where Ms is its Mach number (2/(gamma+1)
// (Ms - 1/Ms) = M/2); it stands still at Ms = M, i.e. M = 2/sqrt(3 - gamma)
// (1.581 for air). Below that it runs upstream, out through an inflow
// boundary whose state is fixed, and piles up there.
double rest_start_min_mach(double gamma);

// Stagnation-point pressure of a blunt body over the free-stream static
// pressure (Rayleigh pitot formula): a normal shock, then isentropic
// compression to rest. Exact for inviscid flow; M <= 1 gives the isentropic
// stagnation pressure.
double rayleigh_pitot_ratio(double mach, double gamma);

// Billig (1967) correlations, gamma = 1.4. Standoff over nose radius, and the
// shock curvature radius over nose radius.
double billig_standoff_cylinder(double mach);   // 0.386 exp(4.67/M^2)
double billig_standoff_sphere(double mach);     // 0.143 exp(3.24/M^2)
double billig_shock_radius_cylinder(double mach);  // 1.386 exp(1.8/(M-1)^0.75)
// Billig's hyperbola: distance downstream of the shock vertex at height y,
// for nose radius R. x = Rc cot^2(mu) [sqrt(1 + y^2 tan^2(mu)/Rc^2) - 1].
double billig_shock_x(double mach, double radius, double y);
// Inverse: height of the shock at distance x downstream of its vertex.
double billig_shock_y(double mach, double radius, double x);

}  // namespace scene
