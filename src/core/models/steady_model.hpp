/// Steady FastSim as a ContactModel: no memory, the patch follows the Hertz scaling of the load,
/// or the step's own a, b (and mu) where given, or marches a shape's strips (StepInput::shape; the
/// mesh is then the strips', whichever Mesh was chosen).
/// V < 0 marches the mirror image (rolling_direction.hpp). Units as in contact_model.hpp.
#pragma once

#include "core/calibration/calibration_table.hpp"
#include "core/fastsim/fastsim.hpp"
#include "wheel_rail_contact/contact_model.hpp"
#include "wheel_rail_contact/geometry/hertz.hpp"

namespace wheel_rail_contact {

class SteadyModel : public ContactModel {
 public:
  /// Which mesh the march runs on: fitted to each step's patch (every node loaded; the model's
  /// own choice), or NssModel's fixed mesh as sized for fz_max, the nodes outside the patch
  /// skipped (the same-mesh reference for nss on the fixed mesh in the benchmarks); unlike
  /// NssModel's it never grows: a patch beyond it is clipped onto it.
  enum class Mesh { kFittedToPatch, kSizedForFzMax };
  /// `calibration`: the calibrated FastSim's table (empty: classic FastSim); of several meshes,
  /// the one nearest p.nx (CalibrationTable::forMesh).
  explicit SteadyModel(const ContactParameters& p, Mesh mesh = Mesh::kFittedToPatch,
                       const CalibrationTable& calibration = CalibrationTable());
  StepOutput step(const StepInput& in) override;
  void reset() override { last_ = StepOutput(); }
  std::string name() const override { return "steady"; }
  /// The last march's traction on mesh(), in the march's frame: mirrored (x -> -x, tx negated)
  /// after a step with V < 0.
  const TractionField& traction() const { return field_; }
  const PatchMesh& mesh() const { return mesh_; }

 private:
  ContactParameters p_;
  ReferencePatch ref_;
  CreepCoefficients c_;  // Kalker's, at a/b ab_
  double ab0_;           // a0/b0: the a/b of every step without per-step geometry
  double ab_;
  CalibrationTable calibrationTable_;
  PatchCalibration calibration_;  // calibrationTable_ at a/b ab_
  PatchMesh mesh_;
  TractionField field_;
  bool fitted_;             // mesh_ follows the patch
  double sizedA_, sizedB_;  // the ellipse mesh's size at construction (back from a shape's strips)
  StepOutput last_;         // held at standstill
};

}  // namespace wheel_rail_contact
