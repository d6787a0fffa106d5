#include "wheel_rail_contact/nss_model.hpp"

#include <cmath>

namespace wheel_rail_contact {

NssModel::NssModel(const ContactParameters& p, const ChiTable& chi)
    : p_(p),
      ref_{p.a0, p.b0, p.fz0},
      kalker_(kalkerCoefficients(p.a0 / p.b0, p.nu)),
      adaptive_(p.mesh == "adaptive"),
      dynamic_(p.model == "nss") {
  for (int k = 0; k < 3; ++k)
    chi_[k] = dynamic_ ? chi.at(static_cast<CreepageKind>(k), p.a0 / p.b0) : ChiParameters{};
  const HertzEllipse largest = ref_.at(adaptive_ ? p.fz0 : effectiveFzMax(p));
  mesh_ = PatchMesh(p.nx, p.ny, largest.a, largest.b);
  spare_ = mesh_;
  state_.resize(mesh_.size());
  remapped_.resize(mesh_.size());
  field_.resize(mesh_.size());
  reset();
}

void NssModel::reset() {
  state_.clear();
  field_.tx.setZero();
  field_.ty.setZero();
  field_.slip.setConstant(false);
  // Until a creepage says otherwise, each direction uses its own pure kind (11 along x, 22 along
  // y).
  wx_[0] = wy_[0] = 1.0;
  wx_[1] = wy_[1] = 0.0;
  last_ = StepOutput();
  lastA_ = 0.0;
  if (adaptive_) mesh_.scale(ref_.a0, ref_.b0);
}

StepOutput NssModel::hold(StepStatus status, const char* why) const {
  StepOutput out = last_;
  out.status = status;
  out.message = why;
  return out;
}

void NssModel::followPatch(const HertzEllipse& h) {
  if (!adaptive_ || (h.a == mesh_.a() && h.b == mesh_.b())) return;
  spare_.scale(h.a, h.b);
  remapState(mesh_, state_, spare_, &remapped_);
  std::swap(state_, remapped_);
  mesh_.scale(h.a, h.b);
}

void NssModel::keepDisplacement(double a) {
  // What persists in the material is the elastic displacement u = L tau (paper eq. 3), and every
  // flexibility L scales with a (a/b is fixed): carry u, not tau, into the new patch size.
  if (lastA_ > 0.0 && a != lastA_) {
    const double r = lastA_ / a;
    state_.tx *= r;
    state_.ty *= r;
    state_.sx *= r;
    state_.sy *= r;
  }
  lastA_ = a;
}

void NssModel::chooseFilters(const Creepages& c, double a, double b, double V, double dt) {
  if (!dynamic_) {
    zx_ = zy_ = FilterZ{};
    return;
  }
  const double spin = std::abs(c.phi) * std::sqrt(a * b);
  if (std::abs(c.xi) + spin > 0.0) {
    wx_[0] = std::abs(c.xi);
    wx_[1] = spin;
  }
  if (std::abs(c.eta) + spin > 0.0) {
    wy_[0] = std::abs(c.eta);
    wy_[1] = spin;
  }
  const FilterZ z11 = discretise(chi_[0], a, V, dt), z22 = discretise(chi_[1], a, V, dt),
                z23 = discretise(chi_[2], a, V, dt);
  zx_ = weightedFilter(z11, wx_[0], z23, wx_[1]);
  zy_ = weightedFilter(z22, wy_[0], z23, wy_[1]);
}

StepOutput NssModel::step(const StepInput& in) {
  StepOutput out;
  if (screenStep(in, &out)) {
    if (out.status == StepStatus::kNoLoad) reset();  // loss of contact clears the history
    return out;
  }
  if (in.V == 0.0) return hold(StepStatus::kStandstill, "V = 0: no travel, state and forces held");
  const HertzEllipse h = ref_.at(in.fz);
  followPatch(h);
  keepDisplacement(h.a);
  parabolicBound(mesh_, h.a, h.b, in.fz, p_.mu, &field_.bound);
  CreepForces f;
  // Travel below 1e-9 a is no travel (a subnormal V made 1 / (V dt) infinite: NaN, found by
  // fuzzing): the step then holds the history as dt = 0 does.
  if (in.dt > 0.0 && in.V * in.dt > 1e-9 * h.a) {
    const Creepages c{in.xi, in.eta, in.phi};
    chooseFilters(c, h.a, h.b, in.V, in.dt);
    f = transientFastSim(mesh_, kalkerFlexibilities(h.a, h.b, p_.G, kalker_), c, in.V, in.dt, zx_,
                         zy_, &state_, &field_);
  } else {
    f = holdTraction(mesh_, &state_, &field_);  // no time has passed: the history stands
  }
  out = stepOutput(f, in.fz, h.a, h.b);
  if (!adaptive_ && (h.a > mesh_.a() * (1 + 1e-12)))
    out.message = "fz exceeds fz_max: the patch is clipped to the fixed mesh";
  last_ = out;
  return out;
}

}  // namespace wheel_rail_contact
