#include "core/models/steady_model.hpp"

#include "core/models/rolling_direction.hpp"
#include "core/models/step_geometry.hpp"

namespace wheel_rail_contact {

SteadyModel::SteadyModel(const ContactParameters& p, Mesh mesh, const CalibrationTable& calibration)
    : p_(p),
      ref_{p.a0, p.b0, p.fz0},
      c_(kalkerCoefficients(p.a0 / p.b0, p.nu)),
      ab0_(p.a0 / p.b0),
      ab_(ab0_),
      calibrationTable_(calibration.forMesh(p.nx)),  // identified per mesh
      fitted_(mesh == Mesh::kFittedToPatch) {
  // Its combined correction filled as the steps reach it: a model made as a patch appears need
  // not compute the whole grid.
  calibrationTable_.at(ab0_, &calibration_);
  const HertzEllipse sized = ref_.at(fitted_ ? p.fz0 : effectiveFzMax(p));
  sizedA_ = sized.a;
  sizedB_ = sized.b;
  mesh_ = PatchMesh(p.nx, p.ny, sized.a, sized.b);
  field_.resize(mesh_.size());
}

StepOutput SteadyModel::step(const StepInput& in) {
  StepOutput out;
  if (screenStep(in, &out)) {
    if (out.status == StepStatus::kNoLoad) last_ = out;
    return out;
  }
  if (in.V == 0.0) {
    out = last_;
    out.status = StepStatus::kStandstill;
    out.message = "V = 0: no travel, forces held";
    return out;
  }
  // Rolling backwards: forward rolling of the mirror image (rolling_direction.hpp).
  const bool backwards = in.V < 0.0;
  const StepInput fwd = backwards ? mirroredInput(in) : in;
  const HertzEllipse h = stepPatch(fwd, ref_);
  const double ab = stepAOverB(fwd, ab0_);
  if (ab != ab_) {  // per-step geometry: Kalker's coefficients at this a/b
    c_ = kalkerCoefficients(ab, p_.nu);
    calibrationTable_.at(ab, &calibration_);
    ab_ = ab;
  }
  if (fwd.shape) {
    mesh_.setStrips(p_.nx, *fwd.shape, h.a, h.b);
  } else if (mesh_.onStrips()) {  // back from a shape's strips to the ellipse's mesh
    mesh_ = PatchMesh(p_.nx, p_.ny, sizedA_, sizedB_);
  }
  if (field_.tx.size() != mesh_.size()) field_.resize(mesh_.size());
  if (fitted_ && !fwd.shape) mesh_.scale(h.a, h.b);
  const Creepages c{fwd.xi, fwd.eta, fwd.phi};
  const double mu = stepMu(fwd, p_.mu);
  const CalibratedStep cal = calibration_.step(h.a, h.b, p_.G, c_, mu * fwd.fz, c);
  flattenedBound(mesh_, h.a, h.b, fwd.fz, mu, cal.boundShape, &field_);
  const CreepForces f = steadyFastSim(mesh_, cal.L, c, &field_);
  out = stepOutput(f, fwd.fz, h.a, h.b);
  if (aOverBHeld(fwd)) out.message = kAOverBHeldMessage;
  if (backwards) mirrorForces(&out);
  last_ = out;
  return out;
}

}  // namespace wheel_rail_contact
