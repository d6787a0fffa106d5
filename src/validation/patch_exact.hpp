/// The exact half-space solution on a contact patch's own gap, the reference the normal problem
/// per patch (normal/patch_normal.hpp) is checked against: a grid on the candidate's contact
/// plane over the region where the bodies interpenetrate undeformed at the approach (the contact
/// lies inside it), the gap h(x, eta) = g(eta) - g(0) + cos(delta(eta)) x^2 / (2 r(eta)) with g
/// interpolated by a cubic (Catmull-Rom) between the gap function's samples (smooth, as the
/// profiles are), delta and r linearly.
#pragma once

#include <memory>

#include "core/exact/halfspace_normal.hpp"
#include "core/exact/halfspace_solver.hpp"
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

/// The tangential forces of the exact solution on a patch, as WheelsetContact's PatchResult gives
/// them: in the candidate's contact frame (x forward, y = z x x, z the normal from the rail into
/// the wheel), on the wheel; mz about the candidate's contact point.
struct ExactTangential {
  double fx = 0.0, fs = 0.0;  ///< [N]
  double mz = 0.0;            ///< [N m]
  double adhesion_fraction = 1.0;
  bool converged = true;  ///< the solver's (HalfspaceSolution::converged)
  int iterations = 0;
};

/// Kalker's exact tangential problem (halfspace_solver.hpp) on an ExactPatch's grid and pressure,
/// for the creepages xi, eta [-], phi [1/m] of the candidate's contact point (patchCreepages;
/// forward rolling, V > 0: for V < 0 the mirror of rolling_direction.hpp applies).
///
/// Frames. The gap's eta points toward the track centre; the contact frame's y is +eta on the
/// right wheel and -eta on the left (creepages.hpp: y = z x x). The solver's grid is laid in the
/// contact frame (the left wheel's pressure mirrored across the grid), centred at (0, y0) with
/// y0 = +eta_offset (right) or -eta_offset (left). The rigid slip at an element is
/// (xi - phi y, eta + phi x) with y measured from the contact point, y = y0 + y_grid: the solver,
/// whose y is y_grid, is given xi - phi y0, and its moment about the grid's centre is carried to
/// the contact point, mz = mz_grid - y0 fx.
///
/// Pressure: the patch's exact pressure, scaled to a normal force `fn` when given (> 0), e.g. to
/// compare with a model run at another solver's normal force on the same patch.
/// Steady: steady rolling (kSteady). Transient: each step() rolls one element length dx() with the
/// given creepages, from the traction left by the previous step (zero after construction or
/// clearHistory()).
class ExactPatchTangential {
 public:
  /// Throws std::invalid_argument if the patch carries no load.
  ExactPatchTangential(const ExactPatch& patch, WheelSide side, double G, double nu,
                       double fn = 0.0, SolverControl control = {});
  ExactTangential steady(const Creepages& w, double mu);
  ExactTangential step(const Creepages& w, double mu);
  void clearHistory();
  /// Rolled distance per transient step: the grid's element length along x [m].
  double dx() const;
  /// The solver, its grid in the contact frame centred at (0, lateralOffset()).
  const HalfspaceSolver& solver() const { return *solver_; }
  double lateralOffset() const { return y0_; }

 private:
  ExactTangential solve(RollingMode mode, const Creepages& w, double mu);
  std::unique_ptr<HalfspaceSolver> solver_;
  double y0_ = 0.0;
};

/// The steady solution in one call (ExactPatchTangential::steady).
ExactTangential exactPatchTangential(const ExactPatch& patch, WheelSide side, double G, double nu,
                                     const Creepages& w, double mu, double fn = 0.0);

}  // namespace wheel_rail_contact
