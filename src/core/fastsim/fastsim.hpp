/// Kalker's FastSim (J.J. Kalker, A fast algorithm for the simplified theory of rolling contact,
/// Vehicle System Dynamics 11, 1982) on a PatchMesh, with the parabolic traction bound.
/// Units: N, m, Pa; flexibilities m/Pa; creepages xi, eta [-], spin phi [1/m].
/// Sign: forces act on the wheel; positive creepage gives a negative force.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <vector>

#include "core/fastsim/patch_mesh.hpp"
#include "wheel_rail_contact/contact_model.hpp"
#include "wheel_rail_contact/geometry/kalker_coefficients.hpp"

namespace wheel_rail_contact {

/// Kalker's flexibilities of the simplified theory [m/Pa]:
/// L1 = 8a/(3 C11 G), L2 = 8a/(3 C22 G), L3 = pi a sqrt(a/b)/(4 C23 G).
struct Flexibilities {
  double L1 = 0.0;
  double L2 = 0.0;
  double L3 = 0.0;
  /// Flexibility of the spin's longitudinal drive, -phi y / L3x, where it differs from L3 (the
  /// calibrated FastSim's second spin parameter, calibration_table.hpp); 0: L3, as in Kalker's
  /// theory.
  double L3x = 0.0;
  /// Coupling of the longitudinal slip to the lateral traction [1/m^2] (the calibrated FastSim's,
  /// calibration_table.hpp): the x drive gains lateralCoupling y tau_y, tau_y the upstream
  /// node's lateral traction, y the strip's lateral position. Odd in y, it adds no force in
  /// linear theory, only a moment; in full slip it turns the traction off the rigid slip's
  /// direction, as the longitudinal displacement that lateral traction makes through Poisson's
  /// ratio does in exact theory. 0: Kalker's FastSim.
  double lateralCoupling = 0.0;
  /// Eta's lateral drive varying along the rolling direction (the calibrated FastSim's,
  /// calibration_table.hpp): the drive eta / L2 becomes etaGain (eta / L2) (1 - etaSlope x), x [m]
  /// from the patch's centre, leading edge at +a. With xi beside eta it turns the saturated
  /// traction along the strip and carries the moment that exact theory keeps there. 0 and 1:
  /// Kalker's FastSim.
  double etaSlope = 0.0;  ///< [1/m]
  double etaGain = 1.0;   ///< [-]
  double spinX() const { return L3x > 0.0 ? L3x : L3; }
};
Flexibilities kalkerFlexibilities(double a, double b, double G, const CreepCoefficients& c);

struct Creepages {
  double xi = 0.0;   ///< longitudinal [-]
  double eta = 0.0;  ///< lateral [-]
  double phi = 0.0;  ///< spin [1/m]
};

/// The march's lateral drive gy + gphi x at x [m] from the patch's centre (gy [Pa/m] as eta / L2,
/// gphi [Pa/m^2] as phi / L3): eta's (Flexibilities::etaSlope, etaGain) and spin's.
struct LateralDrive {
  double gy, gphi;
};
inline LateralDrive lateralDrive(const Flexibilities& L, const Creepages& c) {
  const double gy = c.eta / L.L2, gphi = c.phi / L.L3;
  if (L.etaSlope == 0.0) return {gy, gphi};
  return {gy * L.etaGain, gphi - gy * L.etaGain * L.etaSlope};
}

/// Integrated result of one FastSim evaluation.
struct CreepForces {
  double fx = 0.0;                ///< [N]
  double fy = 0.0;                ///< [N]
  double mz = 0.0;                ///< spin moment about the patch centre [N m]
  double adhesionFraction = 1.0;  ///< loaded area in adhesion / loaded area [-]
};

/// A computed step's output (status ok) from the integrated forces, the load and the patch.
StepOutput stepOutput(const CreepForces& f, double fz, double a, double b);

/// Where the loaded patch begins on one strip of a mesh that may be larger than the patch: the
/// first node with pressure (nx if none) and the step h [m] from the patch's leading edge on that
/// strip, a_j = a sqrt(1 - y_j^2/b^2) (or the mesh's edge, if the patch is clipped), to that node.
/// The patch's edges lie inside the elements of its first and last loaded nodes (node nx-1-first:
/// the patch is symmetric in x): in the quadrature each stands for 1 + w elements, w = h/dx - 1/2
/// in (-1/2, 1/2], the part of the element inside the patch plus what lies between it and the
/// edge. On a mesh fitted to the patch: node 0, h = half an element, w = 0.
struct StripEntry {
  int first = 0;
  double h = 0.0;
  double w = 0.0;
};

struct StripSums;

/// Per-node fields on a PatchMesh (index = mesh.index(i, j)).
struct TractionField {
  Eigen::ArrayXd tx;                           ///< traction on the wheel along x [Pa]
  Eigen::ArrayXd ty;                           ///< traction along y [Pa]
  Eigen::ArrayXd bound;                        ///< mu * pressure, the Coulomb bound [Pa]
  Eigen::Array<bool, Eigen::Dynamic, 1> slip;  ///< node saturated
  std::vector<StripEntry> entry;               ///< per strip, written with the bound
  std::vector<StripSums> stripSums;            ///< the steady march's per-strip sums (its scratch)
  void resize(int n);
};

/// Parabolic pressure of the simplified theory, p = p_s (1 - x^2/a^2 - y^2/b^2) for an ellipse
/// (a, b) on `mesh` (which may be larger than the ellipse), scaled so that the mesh's own
/// quadrature integrates it to exactly fz: saturated FastSim then gives exactly mu*fz. Writes mu*p
/// to field->bound and where the patch begins on each strip to field->entry (sized mesh.ny()
/// here: allocates only on a first call or a new mesh layout). On a mesh larger than the patch a
/// strip's end nodes get mu*p's mean over the part of the strip they stand for (StripEntry), not
/// its value at the node: saturated there, they carry the bound's integral wherever the edge falls.
void parabolicBound(const PatchMesh& mesh, double a, double b, double fz, double mu,
                    TractionField* field);

/// parabolicBound's bound flattened by s, written in the same pass: with p the parabola (1 - r^2
/// in normalised radius), bound = (1 - s) p + s (3/4) p (2 - p / p0), p0 = 2 mu fz / (pi a b) its
/// peak, i.e. a blend towards 1 - r^4, between the parabolic and Hertz's elliptic shape (spin
/// moment at full slip 8/15, 4/7 and 3 pi / 16 of mu fz times the radius), rescaled so that the
/// mesh's node sums (Sum over nodes of a_j / a times the bound) keep the parabolic total. The sums
/// are taken in closed form per strip (from the mesh's shape sums where the patch fills the mesh),
/// not from the nodes. s = 0 is parabolicBound, bit for bit; the patch is the same ellipse. The
/// calibrated FastSim's bound shape (calibration_table.hpp).
void flattenedBound(const PatchMesh& mesh, double a, double b, double fz, double mu, double s,
                    TractionField* field);

/// Raw views of a TractionField for the marches' inner loops: held in registers, they are not
/// reloaded after every store of `slip` (a bool store may alias anything).
struct FieldPointers {
  double* tx;
  double* ty;
  const double* bound;
  bool* slip;
  explicit FieldPointers(TractionField* f)
      : tx(f->tx.data()), ty(f->ty.data()), bound(f->bound.data()), slip(f->slip.data()) {}
  /// Node k outside the patch (zero bound): zero traction, saturated.
  void unloaded(int k) const {
    tx[k] = ty[k] = 0.0;
    slip[k] = true;
  }
};

/// Running sums of one strip, so the march integrates the forces as it goes. Keep it a local that
/// is only ever copied (ForceSums::addStrip takes it by value): then the compiler holds the sums in
/// registers instead of in memory that every field store might alias.
struct StripSums {
  double tx = 0.0, ty = 0.0, xnTy = 0.0;  ///< sums of tx, ty and (x/a) ty over the strip [Pa]
  int stuck = 0, loaded = 0;              ///< nodes in adhesion, nodes with pressure
  /// Saturates (tx, ty) at the bound g (Coulomb, direction kept), stores node k of `f` and adds it.
  /// Inline: it is the inner loop of every FastSim march.
  void node(int k, double xn, double g, double* nodeTx, double* nodeTy, const FieldPointers& f) {
    const double t2 = *nodeTx * *nodeTx + *nodeTy * *nodeTy;
    // Below about 1e-150 Pa the squares underflow (a traction above a zero bound stayed, found by
    // fuzzing): measure |t| by hypot there; the normal path is unchanged.
    const bool tiny = !(t2 > 1e-300);
    const bool slips = tiny ? std::hypot(*nodeTx, *nodeTy) > g : t2 > g * g;
    if (slips) {
      const double s = g / (tiny ? std::hypot(*nodeTx, *nodeTy) : std::sqrt(t2));
      *nodeTx *= s;
      *nodeTy *= s;
    }
    add(k, xn, g, slips, *nodeTx, *nodeTy, f);
  }
  /// Stores node k's final traction (nodeTx, nodeTy), slipping or not, and adds it.
  void add(int k, double xn, double g, bool slips, double nodeTx, double nodeTy,
           const FieldPointers& f) {
    f.tx[k] = nodeTx;
    f.ty[k] = nodeTy;
    f.slip[k] = slips;
    tx += nodeTx;
    ty += nodeTy;
    xnTy += xn * nodeTy;
    loaded += g > 0.0;
    stuck += g > 0.0 && !slips;
  }
};

/// Strip sums into forces and moment (midpoint rule).
class ForceSums {
 public:
  void addStrip(const PatchMesh& mesh, int j, StripSums s);
  /// The same with the strip's end nodes given their extra weight e.w (StripEntry), their
  /// tractions read from tx and ty (indexed as the mesh): kept out of the march's sums, which then
  /// stay in registers.
  void addStrip(const PatchMesh& mesh, int j, StripSums s, const StripEntry& e, const double* tx,
                const double* ty);
  CreepForces forces() const;

 private:
  CreepForces f_;
  double stuck_ = 0.0, loaded_ = 0.0;
};

/// Sum of the traction field into forces and moment (midpoint rule).
CreepForces integrateTraction(const PatchMesh& mesh, const TractionField& field);

/// Whether a march takes its strips in the lanes of vector registers, several strips at a time
/// (strip_lanes.hpp, where this CPU has them: stripLanesAvailable), or one strip at a time (the
/// scalar reference). The two agree within 1e-12 relative (the lanes fuse multiply-adds). kAuto:
/// where the lanes pay (each march's own rule); kOff, kOn: never, always (tests, comparisons).
enum class StripLanes { kAuto, kOff, kOn };
/// Whether this CPU has the marches' lanes (strip_lanes.hpp).
bool stripLanesAvailable();

/// Steady FastSim: marches each strip from the patch's leading edge in adhesion, saturates at the
/// bound. `field.bound` and `field.entry` must be filled (parabolicBound); tx, ty and slip are
/// written. Nodes outside the patch (zero bound) get zero traction, marked slipping, unmarched.
/// The march takes its strips in lanes unless `lanes` is kOff (kAuto: on meshes of at least
/// kSteadyLanesFromNodes nodes a strip).
constexpr int kSteadyLanesFromNodes = 6;
CreepForces steadyFastSim(const PatchMesh& mesh, const Flexibilities& L, const Creepages& c,
                          TractionField* field, StripLanes lanes = StripLanes::kAuto);

}  // namespace wheel_rail_contact
