/// The normal problem on each contact patch the contact search finds: where the wheel and rail
/// touch, the pressure there and the normal force, at a cost of a few microseconds per patch.
///
/// Geometry. On a candidate's contact plane (x along the rolling direction, eta lateral as in
/// ContactCandidate::gap_function) the undeformed gap beyond first touch is
///   h(x, eta) = g(eta) - g(0) + x^2 / (2 R_x(eta)),   1 / R_x = cos(delta(eta)) / r(eta),
/// g the sampled gap function, r and delta the wheel's circle radius and contact angle at eta
/// (Meusnier: the wheel's curvature along its circle, seen in the contact plane); the rail is
/// straight along x (tangent track). An approach d along the candidate's normal makes the bodies
/// interpenetrate by d - h(x, eta) where that is positive.
///
/// Method (doc/normal_problem.md). Let eta0 be the gap function's minimum, d0 = d - h(0, eta0)
/// the deepest interpenetration and A = 1 / (2 R_x(eta0)).
/// - Hertz (kHertz) where the patch is elliptic: over the region h(0, eta) - h(0, eta0) < d0 / 2
///   the gap departs from its least-squares parabola B (eta - eta0)^2 by less than
///   NormalOptions::hertz_tolerance of d0 / 2 and R_x varies by less than that fraction (patches
///   within three samples of the gap function count as elliptic): Hertz's closed form for
///   curvatures A, B and approach d0.
/// - Otherwise (kNonHertzian) Kik-Piotrowski's strips with a y-dependent penetration factor, as
///   CONTACT's KPEC: the region's lateral extent [ys, ye] gives B = (d0/2) / ((ye - ys)/2)^2 about
///   ymid = (ys + ye)/2, Hertz's semi-axes aa, bb for A, B at approach d0, and
///     eps(eta) d0 = A aa^2 - (A aa^2 - B bb^2) ((eta - ymid) / bb)^2.
///   The patch is where h(0, eta) - h(0, eta0) < eps(eta) d0; each strip carries
///   p = P sqrt(L^2 - x^2) over |x| < L(eta) = sqrt((eps d0 - h(0, eta) + h(0, eta0)) 2 R_x(eta)),
///   and the one amplitude P makes the elastic (Boussinesq) displacement at (0, eta0) equal d0.
///   On a Hertz gap this region is Hertz's ellipse and the pressure Hertz's.
///
/// Where it is weak: a gap with a plateau or two lumps under one candidate (near-conformal tread
/// contact): the strips stop where the exact contact spreads over the plateau, fn at a given
/// approach some 30 % low on the Manchester benchmark at 0.5 mm (the patch's message flags a gap
/// that turns concave under the patch, status staying kOk); conformal contact (a flange
/// root hugging the gauge corner, worn profiles), where the half-space and the single contact plane
/// fail as well; very short patches (a << b), where the one displacement condition carries any
/// error of the assumed shape straight into fn. test/unit/test_patch_normal.cpp checks it against
/// the exact half-space solver.
///
/// Units SI: m, N, Pa, rad.
#pragma once

#include <string>
#include <vector>

#include "wheel_rail_contact/profiles/contact_search.hpp"

namespace wheel_rail_contact {

enum class NormalMethod { kHertz, kNonHertzian };

enum class NormalStatus {
  kOk,                 ///< solved (fn = 0 if the patch is not in contact)
  kInvalidInput,       ///< a value not finite or out of range (message names it)
  kNoGapFunction,      ///< the candidate has no (or too short a) gap function
  kBeyondGapFunction,  ///< the patch reaches the end of the sampled gap function: the approach
                       ///< is deeper than the geometry covers (ContactSearchOptions::gap_reach)
  kNoContact,          ///< solveWheelLoad: no candidate, the wheel is not above its rail
  kNotConverged,       ///< solveWheelLoad: the approach iteration did not converge
};

/// One lateral strip of a patch, width `width` centred on `eta`.
struct NormalStrip {
  double eta = 0.0;      ///< lateral centre from the candidate's point [m]
  double width = 0.0;    ///< [m]
  double x_lead = 0.0;   ///< leading edge (+x) of the contact on this strip [m]
  double x_trail = 0.0;  ///< trailing edge [m]
  double pmax = 0.0;     ///< peak pressure on the strip [Pa]
  double force = 0.0;    ///< the strip's normal force [N]
};

struct NormalPatch {
  NormalStatus status = NormalStatus::kOk;
  /// Why a status is not kOk; with kOk, empty or a caution (a gap that turns concave under the
  /// patch, where the strips may miss part of the contact).
  std::string message;
  NormalMethod method = NormalMethod::kHertz;
  double approach = 0.0;  ///< rigid approach along the candidate's normal beyond first touch [m]
  double fn = 0.0;        ///< normal force [N]
  double pmax = 0.0;      ///< peak pressure [Pa]
  /// Equivalent ellipse: b half the lateral extent, a such that pi a b is the contact area (a
  /// along rolling) [m]. Hertz: the ellipse itself.
  double a = 0.0, b = 0.0;
  double eta_centre = 0.0;  ///< lateral centre of the patch from the candidate's point [m]
  double eta_min = 0.0, eta_max = 0.0;  ///< lateral extent [m]
  double area = 0.0;                    ///< contact area [m^2]
  std::vector<NormalStrip> strips;      ///< from eta_min to eta_max
};

struct NormalOptions {
  int strips = 24;  ///< strips across a patch (both methods)
  /// Hertz where the gap departs from its fitted parabola by less than this fraction of half the
  /// deepest interpenetration, and R_x varies by less than this fraction, over the patch.
  double hertz_tolerance = 0.03;
  bool allow_hertz = true;       ///< false: the strip method on every patch (for checks)
  double load_tolerance = 1e-6;  ///< solveWheelLoad: relative error of the vertical load
  int max_iterations = 100;      ///< solveWheelLoad: iterations on the approach
};

/// The normal problem of one candidate at a rigid approach [m] along its normal beyond first
/// touch (approach <= 0: out of contact, fn = 0). G [Pa] > 0, nu in [0, 0.5). Never throws; bad
/// input gives a status and message with zero forces.
NormalPatch solvePatchNormal(const ContactCandidate& candidate, double approach, double G,
                             double nu, const NormalOptions& options = {});

struct WheelNormal {
  NormalStatus status = NormalStatus::kOk;
  std::string message;
  std::vector<NormalPatch> patches;  ///< one per candidate, in the geometry's order
  /// The wheel's vertical approach [m] from the pose the geometry was searched at (down onto the
  /// rail, > 0 to close a gap): candidate i takes the approach
  ///   vertical_approach * n_z,i - gap_i   along its normal (n_z,i its normal's z component).
  double vertical_approach = 0.0;
};

/// The vertical approach at which sum_i fn_i n_z,i = vertical_load [N] (> 0), each candidate's
/// patch solved by solvePatchNormal: two patches share the load by their own stiffness. The gap
/// functions describe the profiles about the searched pose: search near first touch. Never
/// throws; bad input (load not finite or <= 0, no candidate, a patch beyond its gap function)
/// gives a status and message with zero forces.
WheelNormal solveWheelLoad(const WheelContactGeometry& geometry, double vertical_load, double G,
                           double nu, const NormalOptions& options = {});

}  // namespace wheel_rail_contact
