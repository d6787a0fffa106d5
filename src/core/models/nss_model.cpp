#include "core/models/nss_model.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/models/rolling_direction.hpp"
#include "core/models/step_geometry.hpp"

namespace wheel_rail_contact {

NssModel::NssModel(const ContactParameters& p, const ChiTable& chi,
                   const CalibrationTable& calibration)
    : p_(p),
      ref_{p.a0, p.b0, p.fz0},
      kalker_(kalkerCoefficients(p.a0 / p.b0, p.nu)),
      calibrationTable_(calibration.forMesh(p.nx)),  // identified per mesh, as chi
      adaptive_(p.mesh == "adaptive"),
      dynamic_(p.model == "nss"),
      forceWeightedFilters_(!calibration.empty()),
      chiTable_(dynamic_ ? chi.forMesh(p.nx) : ChiTable::uniform({})),  // chi is fitted per mesh
      ab0_(p.a0 / p.b0),
      ab_(ab0_) {
  // Its combined correction filled as the steps reach it: a model made as a patch appears need
  // not compute the whole grid.
  calibrationTable_.at(ab0_, &calibration_);
  // Linear interpolation between two stable second-order rows need not be stable (the Routh
  // condition is not convex in chi): refuse an a/b where it is not.
  if (!pickChi(ab0_, chi_, secondKind_))
    throw std::invalid_argument(
        "nss: the chi table's second-order F at a/b = " + std::to_string(ab0_) + " is not stable");
  const HertzEllipse largest = ref_.at(adaptive_ ? p.fz0 : effectiveFzMax(p));
  mesh_ = PatchMesh(p.nx, p.ny, largest.a, largest.b);
  spare_ = mesh_;
  sizedA_ = largest.a;
  sizedB_ = largest.b;
  growthMargin_ = std::max(1.0, std::cbrt(effectiveFzMax(p) / p.fz0));
  state_.resize(mesh_.size());
  remapped_.resize(mesh_.size());
  // Calibrated: x and y run different filters under a single creepage kind (spin: x on chi11, y on
  // chi23, chooseFilters), and the paper's saturation (the adhesion guess scaled onto the bound)
  // then turned a slipping traction by the two filters' memories, b0 / (V dt): under constant spin
  // the force moved with the step length (Fy 0.30 -> 0.38 mu Fz over 0.01 -> 10 elements).
  // Classic keeps the paper's saturation.
  const TransientState::Saturation saturation =
      forceWeightedFilters_ ? TransientState::Saturation::kResidualAlongTraction
                            : TransientState::Saturation::kAlongGuess;
  state_.setSaturation(saturation);
  remapped_.setSaturation(saturation);
  carry_ = AlongStripMap(p.nx);
  field_.resize(mesh_.size());
  scratch_.resize(mesh_.size());
  firstBefore_.resize(mesh_.ny());
  reset();
}

bool NssModel::pickChi(double ab, SecondOrderChi* chi, bool* secondKind) const {
  for (int k = 0; k < 3; ++k) {
    chi[k] =
        dynamic_ ? chiTable_.secondOrderAt(static_cast<CreepageKind>(k), ab) : SecondOrderChi{};
    secondKind[k] = chi[k].chi4 != 0.0 || chi[k].chi5 != 0.0;
    if (secondKind[k] && !chi[k].valid()) return false;
  }
  return true;
}

bool NssModel::followAOverB(double ab) {
  SecondOrderChi chi[3];
  bool second[3];
  if (!pickChi(ab, chi, second)) return false;
  const CreepCoefficients c = kalkerCoefficients(ab, p_.nu);
  // What persists in the material is the displacement u = L tau (historyScale), and L1, L2 scale
  // with 1 / C11, 1 / C22 as well as with a: carry u along each direction.
  if (lastA_ > 0.0) state_.scaleDirections(c.c11 / kalker_.c11, c.c22 / kalker_.c22);
  kalker_ = c;
  calibrationTable_.at(ab, &calibration_);
  for (int k = 0; k < 3; ++k) {
    chi_[k] = chi[k];
    secondKind_[k] = second[k];
  }
  ab_ = ab;
  reshaped_ = true;
  return true;
}

void NssModel::reshapeHistory(const HertzEllipse& h) {
  // The adaptive mesh carries a load's change along the strips at fixed y/b (AlongStripMap): a and
  // b scale alike there. A new a/b moves b against a, and strips kept at fixed y/b would stretch
  // the history across the patch by b_new/b_old with the force it carries (a/b 1.4 -> 0.7 at the
  // same area: +35 % in Fy at once). So the history is carried at fixed physical coordinates
  // (paper eq. 19) into the new patch, and the march then runs on it in place.
  carryHistoryOnto(h.a, h.b);
}

void NssModel::carryHistoryOnto(double a, double b) {
  spare_.scale(a, b);
  remapState(mesh_, state_, spare_, &remapped_);
  std::swap(state_, remapped_);
  mesh_.scale(a, b);
}

void NssModel::resizeMesh(double a, double b) {
  mesh_.scale(a, b);
  // A patch equal to the mesh up to rounding (fz = fz_max) fits: it fills the mesh.
  fitsA_ = a * (1 + 1e-12);
  fitsB_ = b * (1 + 1e-12);
}

void NssModel::growMesh(const HertzEllipse& h, bool carry) {
  // Grown with the margin the mesh was given over the patch at fz0, so that a patch which keeps
  // growing regrows seldom, and a patch of a0/b0's shape keeps the node density it had there (a
  // patch doubled at the same load and a/b gives four times the force, as on the adaptive mesh).
  const double a = std::max(mesh_.a(), growthMargin_ * h.a),
               b = std::max(mesh_.b(), growthMargin_ * h.b);
  if (carry && lastA_ > 0.0) carryHistoryOnto(a, b);  // lastA_ == 0: no history yet
  resizeMesh(a, b);
  // The history now sits on other nodes: the trailing nodes the patch newly covers on this step
  // keep what the carrying gave them (coverTrailingNodes copies nothing this once).
  std::fill(firstBefore_.begin(), firstBefore_.end(), 0);
}

void NssModel::dropSecondState() {
  // A first-order march neither reads nor writes s2, so it must find zeros there when a
  // second-order step comes back. Both buffers: the moving march writes remapped_.
  state_.secondState().setZero();
  remapped_.secondState().setZero();
  secondOrder_ = handingOn_ = false;
}

void NssModel::sizeBuffers(int n, bool keepState) {
  if (field_.tx.size() == n) return;
  if (!keepState) state_.resize(n);
  remapped_.resize(n);
  field_.resize(n);
  scratch_.resize(n);
}

void NssModel::leaveStrips(const HertzEllipse& h, bool carry) {
  if (adaptive_) mesh_.scale(h.a, h.b);
  const bool carried = carry && lastA_ > 0.0;
  if (carried) {
    remapAtFixedPoints(stripMesh_, stripOrigin_, state_, mesh_, stripOrigin_, &remapped_);
    std::swap(state_, remapped_);
  }
  // state_ is sized already when carried (resizing would clear it): the rest follow.
  sizeBuffers(mesh_.size(), carried);
  if (!carried) state_.clear();
  // The history now sits on other nodes: the fixed mesh's trailing nodes keep what the carrying
  // gave them (coverTrailingNodes copies nothing this once).
  std::fill(firstBefore_.begin(), firstBefore_.end(), 0);
  onStrips_ = false;
}

namespace {

// The share of the reference point's move on the rail's profile that the history's frame follows
// on strips. FastSim's strips share nothing across: a column of material that a sliding patch
// newly covers starts from zero, where exact theory's traction spreads into it from its
// neighbours. Carried at fixed points of the profile (share 1) the history lost so much more than
// exact theory's as an ellipse slid sideways that nss's force fell up to 5 % of mu fz below exact's
// sliding a hundredth of b per element rolled, 19 % at a tenth; carried with the contact point
// (share 0) it kept what exact theory loses, up to 19 % above. Half: within 2 % at a hundredth,
// 9 % at a tenth, over xi, eta and spin (doc/true_patch.md).
constexpr double kCarriedShare = 0.5;

// Whether the lateral extents of two strip meshes, each at its origin on the profile, overlap.
bool overlapOnProfile(const PatchMesh& a, double originA, const PatchMesh& b, double originB) {
  auto extent = [](const PatchMesh& m, double origin, double* lo, double* hi) {
    *lo = origin + m.stripY(0) - 0.5 * m.stripWidth(0);
    *hi = origin + m.stripY(m.ny() - 1) + 0.5 * m.stripWidth(m.ny() - 1);
  };
  double loA, hiA, loB, hiB;
  extent(a, originA, &loA, &hiA);
  extent(b, originB, &loB, &hiB);
  return loA < hiB && loB < hiA;
}

}  // namespace

StepOutput NssModel::stepOnStrips(const StepInput& in, const HertzEllipse& h, bool steady) {
  reshaped_ = false;  // the carrying below is at fixed physical coordinates already
  const double origin = in.shape->origin;
  nextStrips_.setStrips(p_.nx, *in.shape, h.a, h.b);
  const char* note = "";
  if (!steady && lastA_ > 0.0) {
    const PatchMesh& from = onStrips_ ? stripMesh_ : mesh_;
    // An ellipse's history has no position on the profile: taken as centred on this reference.
    const double fromOrigin = onStrips_ ? stripOrigin_ : origin;
    // Carried at fixed points of a frame that follows half the reference point's move on the
    // profile (kCarriedShare), unless the new patch lies clear of the old one on the profile: then
    // nothing of it was in contact, and it starts from rest.
    const bool clear = !overlapOnProfile(from, fromOrigin, nextStrips_, origin);
    double carried = 0.0;
    if (clear) {
      state_.resize(nextStrips_.size());
    } else {
      carried = remapAtFixedPoints(from, kCarriedShare * fromOrigin, state_, nextStrips_,
                                   kCarriedShare * origin, &remapped_);
      std::swap(state_, remapped_);
    }
    // Said only where the history mattered: a step that rolls farther than the patch's length
    // has carried every loaded particle out of the patch anyway.
    if (carried == 0.0 && in.V * in.dt < 2.0 * h.a)
      note =
          "the patch moved clear of its previous position on the profile: no history to carry, "
          "it starts from rest";
  } else {
    state_.resize(nextStrips_.size());
  }
  std::swap(stripMesh_, nextStrips_);
  onStrips_ = true;
  stripOrigin_ = origin;
  remapped_.resize(stripMesh_.size());
  if (field_.tx.size() != stripMesh_.size()) {
    field_.resize(stripMesh_.size());
    scratch_.resize(stripMesh_.size());
  }
  CreepForces f;
  const Creepages c{in.xi, in.eta, in.phi};
  if (steady) {
    followBranch(in, -1.0, h.a);
    const CalibratedStep cal = calibrated(h, in);
    boundOn(stripMesh_, h, in, cal.boundShape);
    updateWeights(c, h.a, h.b);
    lastSpeed_ = in.V;
    lastA_ = h.a;
    f = steadyFastSim(stripMesh_, cal.L, c, &field_);
    state_.tx() = field_.tx.transpose();
    state_.ty() = field_.ty.transpose();
    state_.sx().setZero();
    state_.sy().setZero();
    if (secondOrder_) dropSecondState();
  } else {
    followBranch(in, in.dt > 0.0 ? in.V * in.dt : 0.0, h.a);
    const CalibratedStep cal = calibrated(h, in);
    boundOn(stripMesh_, h, in, cal.boundShape);
    if (!(in.dt > 0.0 && in.V * in.dt > 1e-9 * h.a)) {
      f = holdTraction(stripMesh_, &state_, &field_);
    } else {
      keepRatePerTravel(in.V);
      chooseFilters(c, h.a, h.b, in.V, in.dt);
      // On strips the history is carried as traction (r = 1), not as the displacement L tau that
      // historyScale keeps when an ellipse's a changes with the load: a non-Hertzian patch's
      // equivalent a (its area over pi b) jumps when its outline does (the strips spreading over a
      // tread's plateau: 2.7 -> 1.6 mm in one step), and carrying L tau through it scaled the
      // traction by 1.7 at once, a force spike its steady limit does not show. The carrying at
      // fixed points (above) already follows the strips' own change of length.
      const double r = 1.0;
      lastA_ = h.a;
      f = transientFastSim(stripMesh_, cal.L, c, in.V, in.dt, zx_, zy_, r, &state_, &field_,
                           handingOn_);
      if (handingOn_) dropSecondState();
    }
  }
  StepOutput out = finish(f, in, h, false);
  if (*note)
    out.message = note;
  else if (aOverBHeld(in))
    out.message = kAOverBHeldMessage;
  last_ = out;
  return out;
}

void NssModel::reset() {
  if (onStrips_) {
    sizeBuffers(mesh_.size());
    onStrips_ = false;
  }
  state_.clear();
  dropSecondState();
  field_.tx.setZero();
  field_.ty.setZero();
  field_.slip.setConstant(false);
  // Until a creepage says otherwise, each direction uses its own pure kind (11 along x, 22 along
  // y).
  wx_[0] = wy_[0] = 1.0;
  wx_[1] = wy_[1] = 0.0;
  last_ = StepOutput();
  lastA_ = 0.0;
  if (ab_ != ab0_) followAOverB(ab0_);  // a fresh model's coefficients (no history to carry)
  reshaped_ = false;
  lastSpeed_ = 0.0;
  opposed_ = -1.0;
  std::fill(firstBefore_.begin(), firstBefore_.end(), p_.nx);  // no node loaded
  frame_.reset();
  if (adaptive_)
    mesh_.scale(ref_.a0, ref_.b0);
  else
    resizeMesh(sizedA_, sizedB_);  // a grown mesh too: there is no history left to hold
}

StepOutput NssModel::hold(StepStatus status, const char* why) const {
  StepOutput out = last_;
  out.status = status;
  out.message = why;
  return out;
}

bool NssModel::meshMustFollow(const HertzEllipse& h) const {
  return adaptive_ && (h.a != mesh_.a() || h.b != mesh_.b());
}

bool NssModel::patchMoves(const HertzEllipse& h) {
  if (!meshMustFollow(h)) return false;
  spare_.scale(h.a, h.b);
  carry_.set(h.a / mesh_.a());
  return true;
}

void NssModel::adoptMovedPatch() {
  std::swap(state_, remapped_);
  mesh_.scale(spare_.a(), spare_.b());  // the same layout: only the size moves
}

void NssModel::coverTrailingNodes() {
  // Material crosses the trailing edge outwards even while the edge moves back (at |da/dt| < V),
  // so a node the growing patch newly covers there holds material come from upstream, still in
  // contact: its traction history is its upstream node's, not the zero it had outside. Left at
  // zero, the time term held its traction down (doc/validation.md, varying load). The filter
  // state stays the node's own (copying it too was no better). At the leading edge the material
  // entering is unloaded: zero is right there.
  const int nx = mesh_.nx();
  for (int j = 0; j < mesh_.ny(); ++j) {
    const int before = firstBefore_[j], now = std::min(field_.entry[j].first, nx);
    firstBefore_[j] = now;
    if (now >= before || 2 * before >= nx + nx % 2) continue;  // not grown, or newly loaded
    for (int i = nx - before; i < nx - now; ++i)
      state_.copyTraction(mesh_.index(i - 1, j), mesh_.index(i, j));
  }
}

void NssModel::boundOn(const PatchMesh& mesh, const HertzEllipse& h, const StepInput& in,
                       double shape) {
  flattenedBound(mesh, h.a, h.b, in.fz, stepMu(in, p_.mu), shape, &field_);
}

CalibratedStep NssModel::calibrated(const HertzEllipse& h, const StepInput& in) const {
  // Calibrated: a new flexibility each step from its creepages, constant over the patch during the
  // step, and the bound's shape from spin's share of them. The history stays traction (the state
  // the bound limits); only the drive w / L changes, as it does with the creepages themselves.
  const Creepages c{in.xi, in.eta, in.phi};
  return calibration_.step(h.a, h.b, p_.G, kalker_, stepMu(in, p_.mu) * in.fz, c,
                           opposed_ >= 0.0 ? opposed_ : PatchCalibration::opposedBranch(c));
}

void NssModel::followBranch(const StepInput& in, double travel, double a) {
  // The correction was identified apart for eta phi > 0 and < 0, and its bound shape decides how
  // the saturated traction splits. At a reversal eta changes sign at once in the forward frame
  // while the traction standing in the patch is carried on: switching branches there moved the
  // bound under that traction within no travel (a force jump of tens of times what the step's
  // travel allows). The steady traction of the other branch builds as material crosses the
  // patch, so the branch's weight follows over travel with relaxation length a.
  opposed_ = PatchCalibration::followedBranch(opposed_, {in.xi, in.eta, in.phi}, travel, a);
}

double NssModel::historyScale(double a) const {
  // What persists in the material is the elastic displacement u = L tau (paper eq. 3), and every
  // flexibility L scales with a at a given a/b: carry u, not tau, into the new patch size, i.e.
  // read the history times a_old / a (folded into the march's constants). A change of a/b moves
  // L1, L2 further through C11, C22: followAOverB carries that part.
  return lastA_ > 0.0 ? lastA_ / a : 1.0;
}

void NssModel::keepRatePerTravel(double speed) {
  // F(k) acts in the rolled distance (i k <-> (a/V) d/dt); the filter state is a traction rate
  // d/dt at the speed of the step that left it. Carry the rate per unit travel, s / V, into a new
  // speed: else a wheel crawling to a stop keeps moving its traction at the old rate with no
  // travel (V = 1e-9 m/s drove the force to saturation).
  if (lastSpeed_ > 0.0 && speed != lastSpeed_) {
    const double r = speed / lastSpeed_;
    // s2 is a rate too (transposed direct form II: a combination of past g and h) [Pa/s].
    state_.scaleStates(r, secondOrder_);
  }
  lastSpeed_ = speed;
}

void NssModel::updateWeights(const Creepages& c, double a, double b) {
  const double spin = std::abs(c.phi) * std::sqrt(a * b);
  if (std::abs(c.xi) + spin > 0.0) {
    wx_[0] = std::abs(c.xi);
    wx_[1] = spin;
  }
  // Classic: paper eq. 15, |eta| against |phi| sqrt(ab). Calibrated: each kind by the linear force
  // its drive puts along y, C22 |eta| against C23 |phi| sqrt(ab) (times G a b): the filter acts on
  // the traction, and in adhesion eta's and spin's tractions integrate to those forces (the
  // flexibilities L2 and L3 differ by C22 / C23, which eq. 15 leaves out).
  const double etaWeight = forceWeightedFilters_ ? kalker_.c22 : 1.0,
               spinWeight = forceWeightedFilters_ ? kalker_.c23 : 1.0;
  if (std::abs(c.eta) + spin > 0.0) {
    wy_[0] = std::abs(c.eta) * etaWeight;
    wy_[1] = spin * spinWeight;
  }
}

FilterZ NssModel::discretiseKind(int k, double a, double V, double dt) const {
  const SecondOrderChi& c = chi_[k];
  return secondKind_[k] ? discretise(c, a, V, dt)
                        : discretise(ChiParameters{c.chi1, c.chi2, c.chi3}, a, V, dt);
}

void NssModel::chooseFilters(const Creepages& c, double a, double b, double V, double dt) {
  if (!dynamic_) {
    zx_ = zy_ = FilterZ{};
    return;
  }
  updateWeights(c, a, b);
  const FilterZ z11 = discretiseKind(0, a, V, dt), z22 = discretiseKind(1, a, V, dt),
                z23 = discretiseKind(2, a, V, dt);
  // Calibrated: x takes kind 11's filter whatever the spin. Along each strip the x drive,
  // xi - phi y, is uniform in x, the shape of the drive chi11 was identified on, and spin's part
  // puts no force along x; chi23 was identified on y's drive phi x, linear along the strip, and
  // blended into x it cut the time term of xi's traction wherever spin was present
  // (doc/calibrated_fastsim.md, "Non-steady accuracy"). Classic keeps the paper's eq. 15.
  zx_ = forceWeightedFilters_ ? z11 : weightedFilter(z11, wx_[0], z23, wx_[1]);
  zy_ = weightedFilter(z22, wy_[0], z23, wy_[1]);
  const bool second = zx_.secondOrder() || zy_.secondOrder();
  // The step after a second-order F ends (spin stopped) still marches s2, with b2 = a2 = 0: it
  // hands the s2 left by the last second-order step on into s1, as the transposed form does when
  // its coefficients switch, rather than drop it (a jump in the traction).
  handingOn_ = secondOrder_ && !second;
  secondOrder_ = second || handingOn_;
}

CreepForces NssModel::advance(const StepInput& in, const HertzEllipse& h, bool moves) {
  // When the adaptive patch moves, the step runs on spare_ and carries the history over from mesh_
  // along the strips as it marches (AlongStripMap) into remapped_; adoptMovedPatch() then swaps.
  const PatchMesh& mesh = moves ? spare_ : mesh_;
  followBranch(in, in.dt > 0.0 ? in.V * in.dt : 0.0, h.a);
  const CalibratedStep cal = calibrated(h, in);
  boundOn(mesh, h, in, cal.boundShape);
  if (!adaptive_) coverTrailingNodes();
  // Travel below 1e-9 a is no travel (a subnormal V made 1 / (V dt) infinite: NaN, found by
  // fuzzing): the step then holds the history as dt = 0 does, saturated at the current load.
  if (!(in.dt > 0.0 && in.V * in.dt > 1e-9 * h.a)) {
    if (!moves) return holdTraction(mesh, &state_, &field_);
    remapAlongStrips(carry_, state_, mesh_.ny(), &remapped_);
    return holdTraction(mesh, &remapped_, &field_);
  }
  const Creepages c{in.xi, in.eta, in.phi};
  keepRatePerTravel(in.V);
  chooseFilters(c, h.a, h.b, in.V, in.dt);
  const Flexibilities& L = cal.L;
  const double r = historyScale(h.a);
  lastA_ = h.a;
  const CreepForces f =
      moves ? transientFastSim(mesh, L, c, in.V, in.dt, zx_, zy_, r, carry_, state_, &remapped_,
                               &field_, handingOn_)
            : transientFastSim(mesh, L, c, in.V, in.dt, zx_, zy_, r, &state_, &field_, handingOn_);
  // Handed on: s2 is zero in the buffer just written; clear the other one too (first order now).
  if (handingOn_) dropSecondState();
  return f;
}

bool NssModel::screen(const StepInput& given, StepInput* in, HertzEllipse* h, StepOutput* out) {
  if (screenStep(given, out)) {
    if (out->status == StepStatus::kNoLoad) reset();  // loss of contact clears the history
    return false;
  }
  if (given.V == 0.0) {
    *out = hold(StepStatus::kStandstill, "V = 0: no travel, state and forces held");
    return false;
  }
  // A new a/b (per-step geometry) re-picks chi and Kalker's coefficients; absent, a/b stays a0/b0.
  const double ab = stepAOverB(given, ab0_);
  if (ab != ab_ && !followAOverB(ab)) {
    *out = StepOutput();
    out->status = StepStatus::kRejected;
    out->message = "nss: the chi table's second-order F is not stable at this step's a/b";
    return false;
  }
  // V < 0: the mirror image rolls forwards. At a reversal the traction standing in the material
  // stays where it is: carry it into the other direction's frame rather than clear it (a braked
  // wheel that reverses keeps its grip).
  *in = frame_.face(given, [this] {
    mirrorAlongX(mesh(), &state_);
    mirrorAlongX(mesh(), &field_);
  });
  *h = stepPatch(*in, ref_);
  return true;
}

StepOutput NssModel::finish(const CreepForces& f, const StepInput& in, const HertzEllipse& h,
                            bool grew) {
  StepOutput out = stepOutput(f, in.fz, h.a, h.b);
  frame_.toContact(&out);
  if (!adaptive_ && !in.shape) {
    if (grew)
      out.message = in.a != 0.0
                        ? "the step's patch exceeds the fixed mesh (sized for fz_max at a0, b0): "
                          "the mesh grew to hold it, the history carried over (grown until reset "
                          "or loss of contact)"
                        : "fz exceeds fz_max: the fixed mesh grew to hold the patch, the history "
                          "carried over (grown until reset or loss of contact)";
    // A fixed mesh sized far above the load leaves the patch a node or two: the force is then
    // coarse (29 % off at 2 nodes) or zero (inside one element), so say so.
    else if (std::min(h.a / mesh_.a() * p_.nx, h.b / mesh_.b() * p_.ny) < 4.0)
      out.message =
          "the patch covers fewer than 4 nodes of the fixed mesh along an axis (fz_max "
          "far above this load): the force is coarse or zero";
  }
  last_ = out;
  return out;
}

StepOutput NssModel::steadyStep(const StepInput& given) {
  StepOutput out;
  StepInput in;
  HertzEllipse h;
  if (!screen(given, &in, &h, &out)) return out;
  if (in.shape) return stepOnStrips(in, h, true);
  if (onStrips_) leaveStrips(h, false);
  reshaped_ = false;
  if (meshMustFollow(h)) mesh_.scale(h.a, h.b);  // no carry: the history is overwritten below
  const bool grew = outgrowsMesh(h);
  if (grew) growMesh(h, false);
  followBranch(in, -1.0, h.a);
  const CalibratedStep cal = calibrated(h, in);
  boundOn(mesh_, h, in, cal.boundShape);
  if (!adaptive_) coverTrailingNodes();
  const Creepages c{in.xi, in.eta, in.phi};
  updateWeights(c, h.a, h.b);
  lastSpeed_ = in.V;
  lastA_ = h.a;
  const CreepForces f = steadyFastSim(mesh_, cal.L, c, &field_);
  // Under constant input the time-term march's fixed point is this traction with the filter at
  // rest (zero traction rate), so the next step() starts from it without a jump.
  state_.tx() = field_.tx.transpose();
  state_.ty() = field_.ty.transpose();
  state_.sx().setZero();
  state_.sy().setZero();
  if (secondOrder_) dropSecondState();
  return finish(f, in, h, grew);
}

StepOutput NssModel::steadyAlongside(const StepInput& given) {
  const StepInput in = frame_.inFrame(given);
  const HertzEllipse h = stepPatch(in, ref_);
  scratch_.bound = field_.bound;
  scratch_.entry = field_.entry;
  const Creepages c{in.xi, in.eta, in.phi};
  const CreepForces f = steadyFastSim(mesh(), calibrated(h, in).L, c, &scratch_);
  StepOutput out = stepOutput(f, in.fz, h.a, h.b);
  frame_.toContact(&out);
  return out;
}

StepOutput NssModel::step(const StepInput& given) {
  StepOutput out;
  StepInput in;
  HertzEllipse h;
  if (!screen(given, &in, &h, &out)) return out;
  if (in.shape) return stepOnStrips(in, h, false);
  if (onStrips_) {
    leaveStrips(h, true);
    reshaped_ = false;  // carried at fixed physical coordinates already
  }
  if (reshaped_ && adaptive_ && lastA_ > 0.0) reshapeHistory(h);
  reshaped_ = false;
  const bool grew = outgrowsMesh(h);
  if (grew) growMesh(h, true);
  const bool moves = patchMoves(h);
  const CreepForces f = advance(in, h, moves);
  if (moves) adoptMovedPatch();
  return finish(f, in, h, grew);
}

}  // namespace wheel_rail_contact
