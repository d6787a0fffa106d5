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
  carry_ = AlongStripMap(p.nx);
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

bool NssModel::patchMoves(const HertzEllipse& h) {
  if (!adaptive_ || (h.a == mesh_.a() && h.b == mesh_.b())) return false;
  spare_.scale(h.a, h.b);
  carry_.set(h.a / mesh_.a());
  return true;
}

void NssModel::settlePatch() {
  std::swap(state_, remapped_);
  mesh_.scale(spare_.a(), spare_.b());  // the same layout: only the size moves
}

double NssModel::historyScale(double a) const {
  // What persists in the material is the elastic displacement u = L tau (paper eq. 3), and every
  // flexibility L scales with a (a/b is fixed): carry u, not tau, into the new patch size, i.e.
  // read the history times a_old / a (folded into the march's constants).
  return lastA_ > 0.0 ? lastA_ / a : 1.0;
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

CreepForces NssModel::advance(const StepInput& in, const HertzEllipse& h, bool moves) {
  // When the adaptive patch moves, the step runs on spare_ and carries the history over from mesh_
  // along the strips as it marches (AlongStripMap) into remapped_; settlePatch() then swaps.
  const PatchMesh& mesh = moves ? spare_ : mesh_;
  parabolicBound(mesh, h.a, h.b, in.fz, p_.mu, &field_.bound);
  if (!(in.dt > 0.0)) {
    if (moves) remapAlongStrips(carry_, state_, mesh_.ny(), &remapped_);
    return integrateTraction(mesh, field_);  // no time has passed: the history stands
  }
  const Creepages c{in.xi, in.eta, in.phi};
  chooseFilters(c, h.a, h.b, in.V, in.dt);
  const Flexibilities L = kalkerFlexibilities(h.a, h.b, p_.G, kalker_);
  const double r = historyScale(h.a);
  lastA_ = h.a;
  return moves ? transientFastSim(mesh, L, c, in.V, in.dt, zx_, zy_, r, carry_, state_, &remapped_,
                                  &field_)
               : transientFastSim(mesh, L, c, in.V, in.dt, zx_, zy_, r, &state_, &field_);
}

StepOutput NssModel::step(const StepInput& in) {
  StepOutput out;
  if (screenStep(in, &out)) {
    if (out.status == StepStatus::kNoLoad) reset();  // loss of contact clears the history
    return out;
  }
  if (in.V == 0.0) return hold(StepStatus::kStandstill, "V = 0: no travel, state and forces held");
  const HertzEllipse h = ref_.at(in.fz);
  const bool moves = patchMoves(h);
  const CreepForces f = advance(in, h, moves);
  if (moves) settlePatch();
  out = stepOutput(f, in.fz, h.a, h.b);
  if (!adaptive_ && (h.a > mesh_.a() * (1 + 1e-12)))
    out.message = "fz exceeds fz_max: the patch is clipped to the fixed mesh";
  last_ = out;
  return out;
}

}  // namespace wheel_rail_contact
