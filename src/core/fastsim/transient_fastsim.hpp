/// The non-steady FastSim step (paper eqs. 12-14): FastSim with the time term of the slip equation
/// s = w - du/dx + (1/V) du/dt kept, the time term passed through the dynamic-flexibility filter
/// (nss_filter.hpp). With F == 1 this is Shen & Li (1996).
/// Units: tractions Pa, filter states Pa/s, V m/s, dt s; shapes: every array has mesh.size()
/// entries indexed by PatchMesh::index(i, j).
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "core/fastsim/discrete_filter.hpp"
#include "core/fastsim/fastsim.hpp"

namespace wheel_rail_contact {

/// Traction history at fixed contact coordinates: what one step leaves for the next.
/// Column k is node k: its traction and filter states side by side, so the march reads and writes a
/// node's history as (x, y) pairs through one pointer (six arrays cost a pointer and two half
/// loads or stores each per node). The rows are read and written by name through tx() ... s2y().
/// Outside a fixed mesh's patch, with a first-order F, a node's traction is zero and its filter
/// state only decays, s <- d s with the same d at every such node; so the march holds those states
/// as s / D (D the product of every d since) and touches only the nodes that cross the patch's
/// edge. The named rows materialize() first: every reader sees the state itself.
class TransientState {
 public:
  /// Rows tx, ty: traction at the previous step [Pa]; sx, sy: filter state (transposed direct form
  /// II) [Pa/s]; s2x, s2y: the second filter state of a second-order F [Pa/s] (a traction rate
  /// like s: in transposed direct form II every state is a combination of past rates g and h),
  /// zero while the filter is first order: the first-order march neither reads nor writes it.
  static constexpr int kRows = 6;
  /// How the march puts a slipping node's traction on the bound. kAlongGuess (the paper's, and
  /// steady FastSim's): the adhesion guess scaled down. kResidualAlongTraction: the traction
  /// whose residual in the discretised slip equation (the slip) lies along it, so that x and y on
  /// different filters do not turn it; the guess's direction when they share a filter, and under
  /// constant input steady FastSim's at every step length (transient_fastsim.cpp,
  /// slipsAlongTheResidual).
  enum class Saturation { kAlongGuess, kResidualAlongTraction };
  void setSaturation(Saturation s) { saturation_ = s; }
  Saturation saturation() const { return saturation_; }
  /// Whether the march takes strips in the lanes of vector registers (StripLanes, fastsim.hpp)
  /// or one at a time. kAuto: on meshes of at least kLanesFromNodes nodes a strip.
  using StripLanes = wheel_rail_contact::StripLanes;
  static constexpr int kLanesFromNodes = 4;
  void setStripLanes(StripLanes use) { stripLanes_ = use; }
  /// Whether a march on strips of nx nodes takes its strips in lanes.
  bool marchesInLanes(int nx) const;
  void resize(int n);
  void clear();
  /// Restores the states held decayed. Const: it changes how the state is stored, not the state.
  void materialize() const {
    if (decaying_) restoreDecayed();
  }
  /// Node `to` takes node `from`'s traction (rows tx, ty, never held decayed: no materializing).
  void copyTraction(int from, int to) { history_.col(to).head<2>() = history_.col(from).head<2>(); }
  /// Multiplies sx, sy (with `second` also s2x, s2y) by r; no materializing needed (D is
  /// unchanged).
  void scaleStates(double r, bool second);
  /// Multiplies every x row (tx, sx, s2x) by rx and every y row by ry; no materializing needed.
  void scaleDirections(double rx, double ry);
  auto tx() { return materialized().row(0); }
  auto ty() { return materialized().row(1); }
  auto sx() { return materialized().row(2); }
  auto sy() { return materialized().row(3); }
  auto s2x() { return history_.row(4); }  // never held decayed
  auto s2y() { return history_.row(5); }
  auto secondState() { return history_.bottomRows<2>(); }  ///< rows s2x, s2y
  auto tx() const { return materializedRows().row(0); }
  auto ty() const { return materializedRows().row(1); }
  auto sx() const { return materializedRows().row(2); }
  auto sy() const { return materializedRows().row(3); }
  auto s2x() const { return history_.row(4); }
  auto s2y() const { return history_.row(5); }

 private:
  friend struct TransientStorage;  // the marches' access to the storage (transient_fastsim.cpp)
  using Rows = Eigen::Array<double, kRows, Eigen::Dynamic>;
  Rows& materialized() {
    materialize();
    return history_;
  }
  const Rows& materializedRows() const {
    materialize();
    return history_;
  }
  void restoreDecayed() const;
  mutable Rows history_;
  // While decaying_: strip j's nodes outside the patch of entry ends_[j] (StripEntry::first, strips
  // of nx_ nodes) hold sx, sy over decay_. from_: per strip, where the march's outside pass starts.
  mutable bool decaying_ = false;
  mutable Eigen::Array2d decay_{1.0, 1.0};
  std::vector<int> ends_, from_;
  std::vector<StripSums> stripSums_;  // the lanes' sums, added in strip order
  bool fromZero_ = false;             // from_ holds zeros for every strip
  int nx_ = 0;
  Saturation saturation_ = Saturation::kAlongGuess;
  StripLanes stripLanes_ = StripLanes::kAuto;
};

/// One step of length dt > 0 at speed V > 0. Marches each strip from the patch's leading edge
/// solving the discretised slip equation with s = 0 for the adhesion guess, saturates at
/// field->bound, then updates `state` from the saturated traction. field->bound and field->entry
/// must be filled (parabolicBound). Nodes outside the patch (zero bound) get zero traction and only
/// their filter state advances.
/// Second order (zx or zy with b2 or a2 != 0, or `marchSecond`) marches s2 as well; first order
/// leaves s2 untouched (the caller keeps it zero, see NssModel::chooseFilters). `marchSecond` with
/// first-order filters hands the s2 left by a second-order step on into s1 and leaves s2 = 0.
/// The stored history is read times `historyScale` (1: as stored), so a caller can rescale it to a
/// new patch size without a pass over the state; the state written is unscaled.
CreepForces transientFastSim(const PatchMesh& mesh, const Flexibilities& L, const Creepages& c,
                             double V, double dt, const FilterZ& zx, const FilterZ& zy,
                             double historyScale, TransientState* state, TractionField* field,
                             bool marchSecond = false);

/// How the adaptive mesh carries its history when the patch changes size (a choice beyond the
/// paper's eq. 19, see doc/method.md#adaptive-mesh): every strip keeps its own history (strip j of
/// the new patch reads strip j of the old one, i.e. the strips stay at the same y/b), and along the
/// strip the history is carried at fixed physical x by linear interpolation, falling to zero at the
/// old strip's ends (half an element beyond its first and last node) and zero outside them. Every
/// strip's length scales by the same a_new / a_old, so the weights depend on the node index only:
/// one table per step, for any number of strips.
class AlongStripMap {
 public:
  /// For strips of nx nodes (nx >= 2); allocates here, set() does not.
  explicit AlongStripMap(int nx = 2);
  /// The patch's a changes by `ratio` = a_new / a_old.
  void set(double ratio);
  int nodes() const { return static_cast<int>(offset_.size()); }
  /// New node i reads old nodes index(i) and index(i) + 1 of its strip with weights(i).
  int index(int i) const { return static_cast<int>(offset_[i] / TransientState::kRows); }
  Eigen::Array2d weights(int i) const { return {weights_(0, i), weights_(2, i)}; }
  /// index(i) and weights(i) for every i as raw arrays, for loops that must not reload them after
  /// every store: index(i) as the old node's offset in a strip of TransientState::history
  /// (index(i) times its rows), the weights spread for (x, y) pairs: w0, w0, w1, w1 node after
  /// node (16-byte aligned pairs).
  const std::ptrdiff_t* historyOffsets() const { return offset_.data(); }
  const double* spreadWeights() const { return weights_.data(); }
  /// The weighted pair at `nodes` (old node index(i) of a strip) of a per-node field.
  static double read(const double* nodes, const Eigen::Array2d& w) {
    const Eigen::Array2d s = w * Eigen::Map<const Eigen::Array2d>(nodes);
    return s(0) + s(1);
  }

 private:
  // index(i) times TransientState::kRows, pointer-sized: the march adds it to a pointer as it is.
  std::vector<std::ptrdiff_t> offset_;
  Eigen::Array<double, 4, Eigen::Dynamic> weights_;  // w0, w0, w1, w1 per node
};

/// The same step when the load changed the patch size on the adaptive mesh: each node reads
/// `previous` (the history left on the old patch) carried by `map` as the march reaches it, so the
/// carrying costs no pass of its own; the new history goes to *state (sized for mesh; not
/// `previous`). Equals remapAlongStrips followed by the step above.
CreepForces transientFastSim(const PatchMesh& mesh, const Flexibilities& L, const Creepages& c,
                             double V, double dt, const FilterZ& zx, const FilterZ& zy,
                             double historyScale, const AlongStripMap& map,
                             const TransientState& previous, TransientState* state,
                             TractionField* field, bool marchSecond = false);

/// The history of `strips` strips carried by `map` into *out (sized alike).
void remapAlongStrips(const AlongStripMap& map, const TransientState& in, int strips,
                      TransientState* out);

/// A step of dt = 0: no time has passed, so the traction history stands, except that it is
/// saturated at field->bound (filled for the current load): a load that fell since must not leave
/// traction above mu p. Writes the field (saturated nodes marked slipping, the rest keep their
/// flag) and the saturated traction back to `state`; returns the integrated forces.
CreepForces holdTraction(const PatchMesh& mesh, TransientState* state, TractionField* field);

/// Paper eq. 19: carry the history from the patch (from.a(), from.b()) to the patch
/// (to.a(), to.b()) of the same normalised layout by bilinear interpolation at fixed physical
/// coordinates (linear along each strip, then across strips); traction falls to zero at the old
/// patch's edge and is zero outside it. (NssModel uses AlongStripMap instead; see
/// doc/method.md#adaptive-mesh.)
void remapState(const PatchMesh& from, const TransientState& in, const PatchMesh& to,
                TransientState* out);

/// Eq. 19 for meshes of any strips (an ellipse's or a patch's, PatchMesh::setStrips), the patch
/// free to move laterally: carries the history of `from` to `to` at fixed physical coordinates
/// (x along the rolling direction from the patch's centre, Y = origin + y across it, y = stripY,
/// origin the reference point's lateral position in a coordinate attached to the rail's profile:
/// PatchShape::origin). Across strips linear between the centres of two old strips that touch
/// (their edges within 1e-6 of their widths), falling to zero at an old strip's outer edge where no
/// strip touches it (the patch's lateral edges, a gap between two lumps); along each strip linear,
/// falling to zero half an element beyond the old strip's end nodes (as remapState). Sizes *out for
/// `to`. Returns the share of `to`'s strips that received any history (0: the patches do not
/// overlap, the history is lost).
double remapAtFixedPoints(const PatchMesh& from, double fromOrigin, const TransientState& in,
                          const PatchMesh& to, double toOrigin, TransientState* out);

}  // namespace wheel_rail_contact
