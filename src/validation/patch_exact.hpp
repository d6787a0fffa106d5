/// The exact half-space solution on a contact patch's own gap, the reference the normal problem
/// per patch (normal/patch_normal.hpp) is checked against: a grid on the candidate's contact
/// plane over the region where the bodies interpenetrate undeformed at the approach (the contact
/// lies inside it), the gap h(x, eta) = g(eta) - g(0) + cos(delta(eta)) x^2 / (2 r(eta)) with g
/// interpolated by a cubic (Catmull-Rom) between the gap function's samples (smooth, as the
/// profiles are), delta and r linearly.
#pragma once

#include "core/exact/halfspace_normal.hpp"
#include "wheel_rail_contact/profiles/contact_search.hpp"

namespace wheel_rail_contact {

struct ExactPatch {
  NormalSolution solution;
  HalfspaceGrid grid;  ///< centred on (0, eta_offset)
  double eta_offset = 0.0;
  double fn = 0.0, pmax = 0.0;          ///< [N], [Pa]
  double eta_min = 0.0, eta_max = 0.0;  ///< lateral extent of the loaded elements [m]
};

/// The exact solution at a rigid approach [m] beyond first touch on an mx x my grid.
ExactPatch exactPatchNormal(const ContactCandidate& candidate, double approach, double G, double nu,
                            int mx, int my);

/// The exact solutions of all a wheel's candidates at the vertical approach where their vertical
/// forces add up to vertical_load (secant iteration from `vertical_guess`, m); the normal force
/// per candidate [N], 0 for those out of contact.
std::vector<double> exactWheelLoad(const WheelContactGeometry& geometry, double vertical_load,
                                   double G, double nu, int m, double vertical_guess);

}  // namespace wheel_rail_contact
