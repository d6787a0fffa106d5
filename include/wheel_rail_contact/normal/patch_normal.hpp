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
///   NormalOptions::hertz_tolerance of d0 / 2 and R_x varies by less than that fraction; the
///   samples weighted by min(1, 4 (1 - (h - h0) / (d0/2))), 0 at the region's edge, the fit
///   starting from the gap's local parabola at eta0. With r the larger departure over its
///   tolerance: Hertz's closed form for curvatures A, B and approach d0 where r <= 1.
/// - For 1 < r < 2 Hertz's and the strips' solutions blended, the strips' weight
///   w = t^2 (3 - 2t), t = r - 1 (NormalPatch::strip_weight), so that fn, pmax, a, b and the
///   strips are continuous and fn grows monotonically in the approach across the change.
/// - For r >= 2 (kNonHertzian) Kik-Piotrowski's strips with a y-dependent penetration factor, as
///   CONTACT's KPEC: the region's lateral extent [ys, ye] at depth d0/2 gives half-widths
///   cl = eta0 - ys, cr = ye - eta0, B = (d0/2) / ((cl + cr)/2)^2 about ymid = (ys + ye)/2,
///   Hertz's semi-axes aa, bb for A, B at approach d0, and
///     eps(eta) d0 = A aa^2 - (A aa^2 - B bb^2) ((eta - ymid) / bb)^2.
///   The patch is where h(0, eta) - h(0, eta0) < eps(eta) d0 around eta0; each strip carries
///   p = P sqrt(L^2 - x^2) over |x| < L(eta) = sqrt((eps d0 - h(0, eta) + h(0, eta0)) 2 R_x(eta)),
///   and the one amplitude P makes the elastic (Boussinesq) displacement at (0, eta0) equal d0.
///   On a Hertz gap this region is Hertz's ellipse and the pressure Hertz's.
/// - NormalOptions::continuous_region (default): the same with cl, cr the half-widths of the
/// parabola with
///   the gap's interpenetration area at depth d0/2 on that side of eta0,
///   cl = (3/d0) int_{eta<eta0} max(0, d0/2 - h(0, eta) + h(0, eta0)) d eta (likewise cr; on a
///   parabola its extent), ymid = eta0 + (cr - cl)/2, eps held at B bb^2 beyond ymid +- bb where
///   it grows outward, and the patch every part of the gap function where
///   h - h0 < eps d0 (the parts' ends where that quadratic less the gap's line crosses zero),
///   n strips of equal width laid along the parts one after the other. fn, the region's edges and
///   the strips then move continuously with the approach, and fn grows monotonically on the
///   states measured (0.5 to 6.5 mm). Without it (continuous_region = false), beside a tread's
///   plateau (A-2.2 at 0.5 mm) the extent runs over the plateau within a fraction of a micrometre
///   of approach, and the region around eta0 jumps over it when the penetration's dip between
///   fills: fn jumps up and down in the approach, which is why it is not the default.
///   doc/normal_problem.md says what each costs in accuracy there.
///
/// Where it is weak: a gap with a plateau or two lumps under one candidate (near-conformal tread
/// contact): the exact contact spreads over nearly all of the plateau's rigid overlap, the
/// penetration factor, falling away from ymid, stops short of it: fn at a given approach some
/// 23 % low on the Manchester benchmark at 0.5 mm (30 % without continuous_region; the patch's
/// message flags a gap that turns concave under the patch, status staying kOk); conformal contact
/// (a flange root hugging the gauge corner, worn profiles), where the half-space and the single
/// contact plane fail as well; very short patches (a << b), where the one displacement condition
/// carries any error of the assumed shape straight into fn. test/unit/test_patch_normal.cpp checks
/// it against the exact half-space solver.
///
/// Units SI: m, N, Pa, rad.
#pragma once

#include <limits>
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
  /// solveWheelLoad: the candidate whose patch this candidate's has merged into (this one's fn
  /// 0), -1 if none. The merged patch lies in that candidate's contact plane.
  int merged_into = -1;
  /// The strip method's weight in a patch blended from Hertz and the strips (0 for Hertz, 1 for
  /// the strips alone); method names the larger part.
  double strip_weight = 0.0;
};

struct NormalOptions {
  int strips = 24;  ///< strips across a patch (both methods)
  /// Hertz where the gap departs from its fitted parabola by less than this fraction of half the
  /// deepest interpenetration, and R_x varies by less than this fraction, over the patch.
  double hertz_tolerance = 0.03;
  bool allow_hertz = true;  ///< false: the strip method on every patch (for checks)
  /// The strips' half-widths from the interpenetration's area and their region every part where
  /// the penetration is positive (the method above): fn continuous and monotonic in the approach
  /// beside a tread's plateau. false: KPEC's extent at d0/2 and the one region around eta0, whose
  /// pmax on A-2.2's plateau (0.5 mm) is nearer exact's at the load (+0.8 % against -6.6 %) but
  /// whose fn jumps by up to 92 % within 0.01 um of approach there (doc/normal_problem.md).
  bool continuous_region = true;
  double load_tolerance = 1e-6;  ///< solveWheelLoad: relative error of the vertical load
  int max_iterations = 100;      ///< solveWheelLoad: iterations on the approach
  /// solveWheelLoad's warm start: its first trial's vertical approach beyond first touch [m],
  /// e.g. the previous step's WheelNormal::vertical_approach - WheelNormal::touch_approach (under
  /// a load that changes little between steps the approach beyond first touch changes little,
  /// wherever the wheel has moved). NaN (default) or <= 0: a cold start, 10 um. Only the cost
  /// depends on it; the result is the same within load_tolerance.
  double start_beyond_touch = std::numeric_limits<double>::quiet_NaN();
  /// With start_beyond_touch: the load's growth with the approach there, d ln f / d ln(dv -
  /// touch), e.g. the previous step's WheelNormal::load_exponent; NaN or <= 0: 3/2 (Hertz).
  double start_exponent = std::numeric_limits<double>::quiet_NaN();
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
  /// rail, > 0 to close a gap) at which the load balances: candidate i takes the approach
  ///   vertical_approach * n_z,i - gap_i   along its normal (n_z,i its normal's z component).
  double vertical_approach = 0.0;
  /// The vertical approach at which the first candidate touches, min_i gap_i / n_z,i [m].
  double touch_approach = 0.0;
  int trials = 0;  ///< approaches at which the patches were solved
  /// d ln f / d ln(vertical_approach - touch_approach) near the solution, from the last two
  /// trials (3/2 if fewer): NormalOptions::start_exponent for the next step.
  double load_exponent = 1.5;
};

/// The vertical approach at which sum_i fn_i (n_z,i + t_i) = vertical_load [N] (> 0), each
/// candidate's patch solved by solvePatchNormal: two patches share the load by their own
/// stiffness. The gap functions describe the profiles about the searched pose: search near first
/// touch. Never throws; bad input (load not finite or <= 0, no candidate, a patch beyond its gap
/// function) gives a status and message with zero forces.
///
/// t_i = tangential_vertical[i] (all 0 when the vector is empty) is the vertical component of
/// candidate i's tangential force per unit of its normal force: the wheel's load then equals the
/// vertical component of every patch's whole contact force, as a multibody code balances it. With
/// the contact frame of contact_search.hpp (e_x the track's x, e_y = n x e_x = (0, n_z, -n_y)), a
/// tangential force fx e_x + fs e_y has the vertical component -fs n_y, so t_i = -(fs / fn)_i
/// n_y,i, and Coulomb's |(fx, fs)| <= mu fn bounds it by mu |n_y,i|. The caller gives it: the
/// tangential forces depend on fn (WheelsetContact takes each patch's previous step's fs / fn). A
/// merged patch takes the t of the candidate that carries it. Each n_z,i + t_i must be > 0 (the
/// patch's whole force pushes the wheel up as the approach grows, so the force grows monotonically
/// in the approach and the balance has one solution); else, or a vector of another size than the
/// candidates' or with a value not finite: kInvalidInput naming the candidate, zero forces. A
/// patch with n_z + t <= 0 would carry no load however deep (the wheel climbs its flange: Nadal's
/// limit tan(delta) = 1 / mu for a patch in full lateral slip).
///
/// Candidates whose separating ridge lies below the approach form one patch: where the rigid
/// wheel at vertical approach dv overlaps the rail across the ridge between neighbouring
/// candidates (dv n_z > the gap at the ridge, from either side), their gap functions, which the
/// search cuts at that ridge, are joined into the contact plane of the one with the smallest
/// vertical gap (its samples kept, the neighbour's moved by the small angle between the normals)
/// and solved there as one patch, reported at that candidate (message "merged ..."); the others
/// get fn = 0 and merged_into. The merged patch is solved lump by lump: each lump (its part of
/// the gap between the ridges) by the strips above from its own gap at the shared approach, up to
/// the ridge, one amplitude per lump such that the displacement at every lump's deepest point,
/// from all lumps' strips, equals the interpenetration there. Patches not joined across a ridge
/// are solved as by solvePatchNormal. A patch whose gap function ends at a neighbouring
/// candidate with no ridge to join across (a kink between their contact planes) stops at that
/// end (message "cut ...").
///
/// Iteration (doc/normal_problem.md): secant steps on ln f against ln(dv - touch_approach) inside
/// a bracket that bisects when they leave it or stall, to |f - load| <= load_tolerance load.
/// Where the patches' force jumps in the approach across the load (two patches merging across a
/// ridge, a patch cut at a kink), the side whose force is nearer the load is taken once
/// the bracket is 1e-13 m wide: status kOk, the message "the patches' vertical force jumps from
/// ... N to ... N ...". NormalOptions::start_beyond_touch, start_exponent: a warm start.
WheelNormal solveWheelLoad(const WheelContactGeometry& geometry, double vertical_load, double G,
                           double nu, const NormalOptions& options = {},
                           const std::vector<double>& tangential_vertical = {});

}  // namespace wheel_rail_contact
