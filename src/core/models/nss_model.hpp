/// The non-steady FastSim models behind ContactModel: "shen-li" (time term with the static
/// flexibilities, F == 1) and "nss" (Alonso & Gimenez dynamic flexibility with the weighted chi of
/// Guiral et al. 2013, eq. 15), on a fixed mesh (sized for fz_max) or an adaptive one (fitted to
/// the patch, moved only when a(t), b(t) change, the history carried along the strips). V < 0
/// marches the mirror image, the history mirrored at each reversal (rolling_direction.hpp). Units
/// as in contact_model.hpp.
///
/// A step with a shape (StepInput::shape) marches the shape's strips whichever mesh was chosen: the
/// strips are the patch's own (the normal problem's), nx nodes each. Their history is carried from
/// step to step at fixed physical coordinates, laterally in a frame that follows half the
/// reference point's move on the rail's profile (remapAtFixedPoints, kCarriedShare in the source:
/// a patch that changes shape or moves keeps the traction of the material still in contact;
/// where the new patch covers no part of the old one on the profile the history is lost and the
/// step says so). A step without a shape after one with a shape
/// carries the history back onto the ellipse's mesh alike. The buffers are re-sized when the
/// node count changes (the only steps that allocate).
///
/// The fixed mesh never clips a patch: a step whose patch (a load above fz_max, or its own a, b)
/// is longer or wider than the mesh grows the mesh to m times the patch along each axis that needs
/// it, m = (fz_max / fz0)^(1/3) (at least 1; the margin the mesh has over the patch at fz0), and
/// carries the history over at fixed physical coordinates (remapState, as the adaptive mesh does
/// for a new a/b). That step has status kOk and says so in its message. The mesh stays grown until
/// reset() or a loss of contact (which clears the history anyway): shrinking it back when the
/// patch does would remap the history again, and a load oscillating about the threshold would
/// remap it at every crossing.
#pragma once

#include <vector>

#include "core/calibration/calibration_table.hpp"
#include "core/fastsim/transient_fastsim.hpp"
#include "core/models/rolling_direction.hpp"
#include "wheel_rail_contact/contact_model.hpp"
#include "wheel_rail_contact/fastsim/chi_table.hpp"
#include "wheel_rail_contact/fastsim/second_order_flexibility.hpp"
#include "wheel_rail_contact/geometry/hertz.hpp"

namespace wheel_rail_contact {

class NssModel : public ContactModel {
 public:
  /// `chi` is used when p.model == "nss" (shen-li ignores it). Allocates everything here: step()
  /// allocates nothing.
  /// `calibration`: the calibrated FastSim's table (empty: classic FastSim); of several meshes,
  /// the one nearest p.nx (CalibrationTable::forMesh).
  NssModel(const ContactParameters& p, const ChiTable& chi,
           const CalibrationTable& calibration = CalibrationTable());
  StepOutput step(const StepInput& in) override;
  void reset() override;
  std::string name() const override { return p_.model; }

  /// A steady FastSim step on this model's own mesh that leaves its steady traction as the
  /// history (filter at rest): the state the time-term march holds after `in` has been kept for
  /// long. A later step() continues from it without a jump; what the "auto" model runs while the
  /// inputs change slowly.
  StepOutput steadyStep(const StepInput& in);
  /// Steady FastSim for `in` on the mesh and bound the last step() or steadyStep() used, with the
  /// history untouched: what "auto" blends towards when it hands back to steady FastSim.
  StepOutput steadyAlongside(const StepInput& in);

  /// The mesh the history is on: the ellipse's (fixed or adaptive), or the last shape's strips.
  const PatchMesh& mesh() const { return onStrips_ ? stripMesh_ : mesh_; }
  /// The traction on mesh(), in the march's frame: mirrored (x -> -x, tx negated) while V < 0.
  const TractionField& traction() const { return field_; }

 private:
  /// Screens `given` and turns it into the forward-rolling `in` at patch `h`; false when the step
  /// ends there (`out` filled).
  bool screen(const StepInput& given, StepInput* in, HertzEllipse* h, StepOutput* out);
  /// The adaptive mesh must be re-sized to the patch h.
  bool meshMustFollow(const HertzEllipse& h) const;
  bool patchMoves(const HertzEllipse& h);
  void adoptMovedPatch();
  CreepForces advance(const StepInput& in, const HertzEllipse& h, bool moves);
  /// Fixed mesh: the nodes the patch's trailing edge has covered since the last bound take the
  /// traction of the node upstream; then remembers where the patch begins on each strip.
  void coverTrailingNodes();
  double historyScale(double a) const;
  void keepRatePerTravel(double speed);
  void updateWeights(const Creepages& c, double a, double b);
  /// `grew`: the fixed mesh grew on this step (said in the message).
  StepOutput finish(const CreepForces& f, const StepInput& in, const HertzEllipse& h, bool grew);
  void chooseFilters(const Creepages& c, double a, double b, double V, double dt);
  StepOutput hold(StepStatus status, const char* why) const;

  /// A step on a shape's strips (StepInput::shape): the history carried from the previous mesh
  /// (ellipse or strips) at fixed physical coordinates, the patch free to move on the profile
  /// (remapAtFixedPoints); `steady`: steadyStep's, the history overwritten.
  StepOutput stepOnStrips(const StepInput& in, const HertzEllipse& h, bool steady);
  /// Back from a shape's strips onto the ellipse's mesh (fixed, or adaptive at h), the history
  /// carried at fixed physical coordinates unless `carry` is false.
  void leaveStrips(const HertzEllipse& h, bool carry);
  /// The per-node buffers sized for `n` nodes (allocates only when n changes, and clears the
  /// history unless `keepState`: a history carried onto the new mesh already has its size).
  void sizeBuffers(int n, bool keepState = false);
  PatchMesh stripMesh_, nextStrips_;  // the shape's strips: this step's, and the next one's
  bool onStrips_ = false;             // the history lives on stripMesh_ (else on mesh_)
  double stripOrigin_ = 0.0;          // stripMesh_'s PatchShape::origin

  ContactParameters p_;
  ReferencePatch ref_;
  CreepCoefficients kalker_;
  CalibrationTable calibrationTable_;
  PatchCalibration calibration_;  // calibrationTable_ at a/b ab_
  /// The step's traction bound mu p on `mesh` (field_): parabolic, flattened by `shape` (the
  /// calibration's bound shape; classic: 0).
  void boundOn(const PatchMesh& mesh, const HertzEllipse& h, const StepInput& in, double shape);
  /// The step's flexibilities (Kalker's, scaled by the calibration for its creepages) and bound
  /// shape, with the correction's eta phi < 0 branch at weight opposed_.
  CalibratedStep calibrated(const HertzEllipse& h, const StepInput& in) const;
  /// Moves opposed_ towards the branch of this step's eta phi over `travel` [m] (relaxation
  /// length a); negative travel: settled at once (a steady step).
  void followBranch(const StepInput& in, double travel, double a);
  /// Weight of the calibration's eta phi < 0 branch (below 0: none yet, the step's own branch).
  double opposed_ = -1.0;
  bool adaptive_ = false;
  bool dynamic_ = false;  // nss (else shen-li)
  /// Calibrated: each direction's filter blends the kinds by the linear force they put along it
  /// (x: kind 11 alone; y: C22 |eta| against C23 |phi| sqrt(ab)); classic: paper eq. 15.
  bool forceWeightedFilters_ = false;
  ChiTable chiTable_;  // for this mesh (nss), to re-pick chi when a/b changes
  double ab0_ = 1.0;   // a0/b0: the a/b of every step without per-step geometry
  double ab_ = 1.0;    // the a/b kalker_ and chi_ are for
  /// chi of the three kinds at a/b `ab`; false if a second-order one is not stable there.
  bool pickChi(double ab, SecondOrderChi* chi, bool* secondKind) const;
  /// Kalker's coefficients and chi at a/b `ab`, the history carried into them; false (nothing
  /// changed) where chi is not stable.
  bool followAOverB(double ab);
  /// Adaptive mesh after a new a/b: the history carried at fixed physical coordinates into the
  /// patch h, the mesh moved onto it.
  void reshapeHistory(const HertzEllipse& h);
  /// The mesh re-sized to semi-axes (a, b), the history carried at fixed physical coordinates.
  void carryHistoryOnto(double a, double b);
  /// Fixed mesh: the patch h is longer or wider than the mesh.
  bool outgrowsMesh(const HertzEllipse& h) const {
    return !adaptive_ && (h.a > fitsA_ || h.b > fitsB_);
  }
  /// Fixed mesh: grows it to hold the patch h (with the margin growthMargin_); `carry`: the history
  /// carried over (else it is about to be overwritten).
  void growMesh(const HertzEllipse& h, bool carry);
  /// Fixed mesh: the mesh's own size again (a fresh model's).
  void resizeMesh(double a, double b);
  bool reshaped_ = false;  // a/b changed since the last march (followAOverB)
  /// Drops the second filter state of both history buffers (first order from now on).
  void dropSecondState();

  // Kinds 11, 22, 23 at a/b ab_ (a/b does not change with load); first order where the table
  // has no chi4, chi5 (kinds 11, 22; 23 in an older table).
  SecondOrderChi chi_[3];
  bool secondKind_[3] = {false, false, false};  // chi_[k] has chi4 or chi5 != 0
  /// Kind k's filter for a step: the first-order discretise where chi_[k] is first order (spares
  /// the first-order step the second-order dispatch).
  FilterZ discretiseKind(int k, double a, double V, double dt) const;
  PatchMesh mesh_, spare_;
  TransientState state_, remapped_;  // the history; the next one while the patch moves
  AlongStripMap carry_;  // the history's path from the previous patch to this one (adaptive)
  TractionField field_, scratch_;
  std::vector<int> firstBefore_;  // fixed mesh: StripEntry::first per strip at the last bound
  FilterZ zx_, zy_;
  double wx_[2], wy_[2];  // eq. 15 weights (calibrated: y by force), kept while both vanish
  StepOutput last_;
  double lastA_ = 0.0;        // a of the step that left the history (0: none yet) [m]
  double lastSpeed_ = 0.0;    // |V| of the step that left the filter state (0: none yet) [m/s]
  RollingFrame frame_;        // the mirror while rolling backwards
  bool secondOrder_ = false;  // the last step marched s2: state_.s2x/s2y (remapped_'s) may be != 0
  bool handingOn_ = false;    // this step marches s2 only to hand it on into s1 (spin stopped)
  double sizedA_ = 0.0, sizedB_ = 0.0;  // the mesh's size at construction (reset() restores it)
  // Fixed mesh: the largest patch it holds (its size, rounding allowed for), and how much larger
  // than the patch that outgrows it the mesh grows.
  double fitsA_ = 0.0, fitsB_ = 0.0, growthMargin_ = 1.0;
};

}  // namespace wheel_rail_contact
