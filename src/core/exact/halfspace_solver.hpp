/// Kalker's exact theory for the tangential problem of two elastically identical half-spaces on a
/// HalfspaceGrid (CONTACT's split: influence coefficients / this tangential solver / output).
/// Units: tractions and pressures Pa, lengths m, forces N, moment N m, creepages as in fastsim.hpp.
/// Traction and state fields are per grid element (size mx*my, index HalfspaceGrid::index).
/// Slip per unit rolled distance at element I: s_I = w_I + (u_I - u'_I)/dq, with u'_I
///   steady:    u at the upstream neighbour (x + dx) now, dq = dx;
///   transient: u at the upstream neighbour at the previous step, dq = dx (one cell per step);
///   shift:     u at I itself at the previous step, dq the tangential shift (Cattaneo from rest).
/// Rigid slip w = (xi - phi y, eta + phi (x + kSpinOffset dq)) at element centres: in rolling the
/// spin term is taken dq/6 downstream of the centre, as CONTACT does (its "offset 1/6 dq used in
/// rolling problems"); this O(dx) term moves C23 by C22 (dx/6)/sqrt(ab) and makes our C23 equal to
/// CONTACT's. Shift: no offset.
/// Coulomb: |tau| <= mu p; adhesion where |tau| < mu p (s = 0), else tau = -mu p s/|s|.
#pragma once

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/LU>
#include <Eigen/QR>
#include <vector>

#include "core/exact/halfspace_influence.hpp"
#include "core/fastsim/fastsim.hpp"

namespace wheel_rail_contact {

enum class RollingMode { kSteady, kTransient, kShift };

/// Position of the spin rigid slip in rolling, downstream of the element centre, per unit dq.
constexpr double kSpinOffset = 1.0 / 6.0;

namespace detail {
struct ContactRun {
  int ix, lo, len, first;  // grid column, first row, length, index of its first loaded element
};
}  // namespace detail

enum class ElementState : unsigned char { kExterior = 0, kAdhesion, kSlip };

/// Full adhesion is solved directly (Cholesky, or LU for steady rolling, factored once per contact
/// set, used once the set repeats). Partial slip: block Gauss-Seidel with exact 2x2 element solves
/// (the transient problem is a convex minimisation, so the sweeps converge), accelerated by
/// Anderson mixing; it stops when no element's traction moved by more than tolerance * max|tau| in
/// a sweep, and after maxIterations sweeps reports converged = false (its last iterate kept).
/// Memory: two dense (2n)^2 matrices over the n loaded elements (about 35 MB each at 40 x 40).
struct SolverControl {
  double tolerance = 1e-8;
  int maxIterations = 5000;
  /// Steady partial slip is marched in transient steps until no traction changes by more than
  /// steadyTolerance * max|tau| in a step (at most 40 mx steps).
  double steadyTolerance = 1e-7;
  int andersonDepth = 5;  ///< sweeps mixed by Anderson acceleration (0: plain Gauss-Seidel)
};

struct HalfspaceSolution {
  double fx = 0.0;                  ///< [N]
  double fy = 0.0;                  ///< [N]
  double mz = 0.0;                  ///< about the patch centre, sum of (x tau_y - y tau_x) dA [N m]
  Eigen::VectorXd tx, ty;           ///< traction on the wheel [Pa], 0 outside contact
  Eigen::VectorXd sx, sy;           ///< slip per unit rolled distance [-] (shift: per dq)
  std::vector<ElementState> state;  ///< adhesion/slip map
  double adhesionFraction = 1.0;    ///< adhesion elements / contact elements [-]
  int iterations = 0;               ///< Gauss-Seidel sweeps (0: direct adhesion solve sufficed)
  bool converged = true;
  double residual = 0.0;  ///< last sweep's max |delta tau| / max |tau| [-]
  int steadySteps = 0;    ///< transient steps of a steady partial-slip solve
};

class HalfspaceSolver {
 public:
  HalfspaceSolver(const HalfspaceGrid& grid, double G, double nu, SolverControl control = {});
  /// Pressure per element [Pa]; p > 0 marks contact. Outside the grid the traction is zero (a
  /// loaded last column has its upstream neighbour one cell beyond the grid).
  void setPressure(const Eigen::VectorXd& p);
  /// The Hertzian case: the discrete normal problem (halfspace_normal.hpp) for the gap whose Hertz
  /// ellipse at load fz is (a, b), so the loaded elements are those CONTACT loads.
  void setHertzPressure(double a, double b, double fz);
  /// Zero traction history: the next transient or shift step starts from rest.
  void clearHistory();
  /// The traction history reflected x -> -x (element ix swaps with mx-1-ix; tau_x changes sign):
  /// rolling backwards as forwards in the mirror (rolling_direction.hpp).
  void mirrorHistoryAlongX();
  /// One solve; transient and shift use the history and replace it with the result.
  /// dq: shift distance for kShift [m] (ignored otherwise: dq = dx).
  const HalfspaceSolution& solve(RollingMode mode, const Creepages& w, double mu, double dq = 0.0);
  const HalfspaceSolution& solution() const { return sol_; }
  const HalfspaceGrid& grid() const { return kernel_.grid(); }
  const InfluenceKernel& kernel() const { return kernel_; }
  /// Elements in contact (grid indices, ascending).
  const std::vector<int>& contactElements() const { return elems_; }

 private:
  void buildSystem(bool steady);
  void previousDisplacement(RollingMode mode, Eigen::VectorXd* c) const;
  bool directAdhesion(bool steady, const Eigen::VectorXd& rhs, Eigen::VectorXd* tau);
  void gaussSeidel(const Eigen::VectorXd& c, const Creepages& w, double dq, Eigen::VectorXd* tau);
  double sweep(const Eigen::VectorXd& c, const Creepages& w, double dq, Eigen::VectorXd* tau,
               Eigen::VectorXd* v) const;
  void addInfluence(int i, double dx, double dy, Eigen::VectorXd* v) const;
  void recordSlip(const Eigen::VectorXd& c, const Creepages& w, double dq,
                  const Eigen::VectorXd& v);
  void projectOntoDiscs(Eigen::VectorXd* tau, Eigen::VectorXd* v) const;
  void output(const Eigen::VectorXd& tau);
  const HalfspaceSolution& steadyByMarching(const Creepages& w, double mu, Eigen::VectorXd tau);

  InfluenceKernel kernel_;
  double G_, nu_;
  SolverControl control_;
  Eigen::VectorXd p_, bound_;  // per contact element: pressure, mu p
  Eigen::VectorXd slip_;       // per contact unknown (x, y interleaved), of the last solve
  double spinOffset_ = 0.0;    // kSpinOffset dq in rolling, 0 in a shift [m]
  std::vector<int> elems_;
  Eigen::VectorXd histX_, histY_;  // previous traction per grid element
  // System matrix over contact unknowns (x, y interleaved per element), valid for elems_.
  Eigen::MatrixXd m_;
  std::vector<detail::ContactRun> runs_;  // loaded elements as runs of y-neighbours
  int systemKind_ = -1;                   // -1 none, 0 symmetric (transient/shift), 1 steady
  bool systemUsed_ = false;
  bool lastFullAdhesion_ = true;
  Eigen::LLT<Eigen::MatrixXd> llt_;
  Eigen::PartialPivLU<Eigen::MatrixXd> lu_;
  bool factored_ = false;
  HalfspaceSolution sol_;
};

}  // namespace wheel_rail_contact
