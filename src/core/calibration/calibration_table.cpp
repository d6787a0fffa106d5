#include "core/calibration/calibration_table.hpp"

#include "core/calibration/correction_lanes.hpp"
#include "core/csv_fields.hpp"
#include "core/fastsim/nearest_mesh.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string_view>
#include <tuple>

namespace wheel_rail_contact {

namespace {

// The combined correction's ln multiplier p in a cell (PatchCalibration::correctionCell):
// `l0` its first corner, alongT and alongS the strides to the next xi share and spin share, we,
// wt, ws the weights along e, xi's share and spin's share.
inline double inCell(const double* l0, std::size_t alongT, std::size_t alongS, double we, double wt,
                     double ws, int p) {
  constexpr std::size_t P = calibration::kMultipliers;
  auto along = [we](const double* x) { return x[0] + we * (x[P] - x[0]); };
  const double* h0 = l0 + alongS;
  const double l = (1.0 - wt) * along(l0 + p) + wt * along(l0 + alongT + p);
  const double h = (1.0 - wt) * along(h0 + p) + wt * along(h0 + alongT + p);
  return (1.0 - ws) * l + ws * h;
}

// e1^2, e2^2, e3^2 and e (PatchCalibration::normalisedCreepage), here with internal linkage
// so that step() inlines it.
inline double creepageSquares(double a, double b, double G, const CreepCoefficients& k, double muFz,
                              const Creepages& c, double* squares) {
  const double ab = a * b, s = G * ab / muFz;
  const double e1 = s * k.c11 * c.xi, e2 = s * k.c22 * c.eta,
               e3 = s * std::sqrt(ab) * k.c23 * c.phi;
  if (squares) {
    squares[0] = e1 * e1;
    squares[1] = e2 * e2;
    squares[2] = e3 * e3;
  }
  if (!(muFz > 0.0)) return std::numeric_limits<double>::infinity();
  return std::sqrt(e1 * e1 + e2 * e2 + e3 * e3);
}

}  // namespace

double PatchCalibration::normalisedCreepage(double a, double b, double G,
                                            const CreepCoefficients& k, double muFz,
                                            const Creepages& c, double* squares) {
  return creepageSquares(a, b, G, k, muFz, c, squares);
}

inline PatchCalibration::KnotCell PatchCalibration::cell(const std::vector<double>& x,
                                                         const std::vector<double>& perWidth,
                                                         double e) {
  if (!(e < x.back())) return {x.size(), 1.0};  // beyond the last knot (or NaN): held
  // A short table (17 knots): a forward scan is as fast as bisection and branch-predictable.
  const std::size_t i = knotAbove(x, e, 1);
  return {i, (e - x[i - 1]) * perWidth[i]};
}

inline PatchCalibration::KnotCell PatchCalibration::kindCell(double e) const {
  const std::vector<double>& x = eps_[0];
  if (!(e < x.back())) return {x.size(), 1.0};
  const std::size_t i = knotAbove(x, e, knotStart_.at(e));
  return {i, (e - x[i - 1]) * perWidth_[0][i]};
}

void PatchCalibration::setSearchStarts() {
  if (eps_[0].size() >= 2)
    knotStart_.set(eps_[0].back(), [&](double v) { return knotAbove(eps_[0], v, 1); });
  if (corrS3_.empty()) return;
  corrS3Start_.set(1.0, [&](double v) { return spinShareRow(v, 0); });
  corrTStart_.set(1.0, [&](double v) { return xiShareCell(v, 1); });
  corrEpsStart_.set(corrEps_.back(), [&](double v) { return epsCell(v, 1); });
}

double PatchCalibration::logRatio(int kind, double e) const {
  if (eps_[kind].empty()) return 0.0;
  return at(logRatio_[kind], cell(kind, e));
}

double PatchCalibration::boundShape(double a, double b, double G, const CreepCoefficients& k,
                                    double muFz, const Creepages& c) const {
  return step(a, b, G, k, muFz, c).boundShape;
}

void PatchCalibration::correction(const double* e2, double e, bool opposed, int first, int last,
                                  double* m) const {
  for (int p = first; p < last; ++p) m[p] = 1.0;
  if (logCorrection(e2, e, opposed ? 1.0 : 0.0, first, last, m))
    for (int p = first; p < last; ++p) m[p] = std::exp(m[p]);
}

bool PatchCalibration::logCorrection(const double* e2, double e, double opposed, int first,
                                     int last, double* lm) const {
  if (corrS3_.empty() || !(e > 0.0) || !std::isfinite(e)) return false;
  const double rest = e2[0] + e2[1];
  if (!(rest > 0.0) || !(e2[2] > 0.0)) return false;  // one kind, or xi with eta: the rule alone
  lookUpCorrection(e2[2] / (e * e), e2[0] / rest, e, opposed, first, last, lm);
  return true;
}

inline PatchCalibration::CorrectionCell PatchCalibration::correctionCell(double s3, double t,
                                                                         double e) const {
  const std::size_t nS = corrS3_.size(), nT = corrT_.size(), nE = corrEps_.size();
  CorrectionCell c;
  // Spin's share between its knots, the ends 0 and 1 implicit: the cell is [row i - 1, row i].
  std::size_t i = spinShareRow(s3, corrS3Start_.at(s3));
  c.ws = std::min(1.0, (s3 - (i == 0 ? 0.0 : corrS3_[i - 1])) * corrS3PerWidth_[i]);
  ++i;
  const std::size_t j = xiShareCell(t, corrTStart_.at(t));
  c.wt = std::min(1.0, std::max(0.0, (t - corrT_[j - 1]) * corrTPerWidth_[j]));
  std::size_t k = 1;
  c.we = 1.0;
  if (e < corrEps_.back()) {
    k = epsCell(e, corrEpsStart_.at(e));
    c.we = (e - corrEps_[k - 1]) * corrEpsPerWidth_[k];
  } else {
    k = nE - 1;  // held beyond the last knot
  }
  // The cell's four corners (spin-share rows i - 1 and i, xi shares j - 1 and j), each at e's
  // cell [k - 1, k]: the five multipliers of a grid point lie side by side; the eta phi < 0
  // branch's block follows the eta phi > 0 one.
  constexpr std::size_t P = calibration::kMultipliers;
  c.alongT = nE * P;
  c.alongS = nT * c.alongT;
  c.branch = (nS + 2) * c.alongS;
  c.lo = corrLog_.data() + (i - 1) * c.alongS + (j - 1) * c.alongT + (k - 1) * P;
  return c;
}

inline void PatchCalibration::lookUpCorrection(double s3, double t, double e, double opposed,
                                               int first, int last, double* lm) const {
  const CorrectionCell c = correctionCell(s3, t, e);
  fillCell(c, opposed);
  auto multiplier = [&](const double* l0, int p) {
    return inCell(l0, c.alongT, c.alongS, c.we, c.wt, c.ws, p);
  };
  if (opposed <= 0.0) {
    for (int p = first; p < last; ++p) lm[p] = multiplier(c.lo, p);
  } else if (opposed >= 1.0) {
    for (int p = first; p < last; ++p) lm[p] = multiplier(c.lo + c.branch, p);
  } else {
    for (int p = first; p < last; ++p)
      lm[p] = (1.0 - opposed) * multiplier(c.lo, p) + opposed * multiplier(c.lo + c.branch, p);
  }
}

double PatchCalibration::coupling(double e) const {
  return logRatio(calibration::kEtaCoupling, e);  // stored as it is, not as a logarithm
}

double PatchCalibration::etaSlope(double e) const {
  return logRatio(calibration::kEtaDriveSlope, e);  // stored as it is
}

double PatchCalibration::ratio(int kind, double e) const {
  return std::exp(logRatio(kind, e));
}

Flexibilities PatchCalibration::flexibilities(double a, double b, double G,
                                              const CreepCoefficients& k, double muFz,
                                              const Creepages& c) const {
  return step(a, b, G, k, muFz, c).L;
}

CalibratedStep PatchCalibration::step(double a, double b, double G, const CreepCoefficients& k,
                                      double muFz, const Creepages& c) const {
  return step(a, b, G, k, muFz, c, opposedBranch(c));
}

CalibratedStep PatchCalibration::step(double a, double b, double G, const CreepCoefficients& k,
                                      double muFz, const Creepages& c, double opposed) const {
  using namespace calibration;
  CalibratedStep s;
  Flexibilities& L = s.L;
  L = kalkerFlexibilities(a, b, G, k);
  if (classic()) return s;
  double e2[3];
  const double e = creepageSquares(a, b, G, k, muFz, c, e2);
  if (!(e > 0.0)) return s;              // no creepage: linear theory, the parabolic bound
  const bool finite = std::isfinite(e);  // not finite: no friction, full slip (last knot)
  // Every kind's ln ratio at e: one search where the kinds share their knots.
  const KnotCell shared = kindCell(e);
  auto logRatioOf = [&](int kind) {
    return sharedKnots_ ? at(logRatio_[kind], shared) : logRatio(kind, e);
  };
  // Each kind's share of e^2 (one division for the three).
  // (From the squares' sum, not e * e: the division need not wait for e's square root.)
  const double squares = e2[0] + e2[1] + e2[2];
  double share[3] = {0.0, 0.0, 0.0};
  if (finite && squares >= std::numeric_limits<double>::min()) {
    const double perE2 = 1.0 / squares;
    for (int i = 0; i < 3; ++i) share[i] = e2[i] * perE2;
  } else if (finite) {
    // A subnormal sum (creepages near 1e-155): its reciprocal would overflow to infinity.
    for (int i = 0; i < 3; ++i) share[i] = e2[i] / squares;
  }
  // Eta's own ratio, coupling and bound shape without spin (22n, 22cn, 22s), fading into the pair
  // 22, 22c as spin's share goes to kNoSpinTo (noSpinWeight).
  const double noSpin =
      finite && !eps_[kEtaRatioNoSpin].empty() && e2[1] > 0.0 ? noSpinWeight(share[2]) : 0.0;
  auto towardsNoSpin = [&](double withSpin, int kind) {
    return noSpin > 0.0 ? withSpin + noSpin * (logRatioOf(kind) - withSpin) : withSpin;
  };
  // The lateral coupling, times eta's share of the lateral creepages' e2^2 + e3^2 to the sixth:
  // spin's own parameters (23, 23x, 23s) are fitted without it, and on spin's lateral traction it
  // put a moment that those parameters already carry (doc/calibrated_fastsim.md, "What it is",
  // item 6). Where spin is a small share the rest of it is held (heldCoupling), its moment on
  // spin's traction taken back through L3x below. Without eta it is 0; without spin, c itself
  // (c_n); without friction (e infinite, the squares inf or NaN) none: every node slips with zero
  // traction.
  double held = 0.0;
  if (finite && !eps_[kEtaCoupling].empty() && e2[1] > 0.0) {
    static_assert(kCouplingSharePower == 6, "q6 below is q^kCouplingSharePower");
    const double q = e2[1] / (e2[1] + e2[2]), q2 = q * q, q6 = q2 * q2 * q2;
    held = heldCoupling(e, share[2]);
    L.lateralCoupling = lateralCoupling(
        towardsNoSpin(logRatioOf(kEtaCoupling), kEtaCouplingNoSpin) * (q6 + (1.0 - q6) * held), a,
        b, k);
    // Eta's drive's slope where xi is beside eta (etaSlopeWeight): in full slip it turns the
    // traction along the strip, as exact theory's xi = eta curves do (doc/calibrated_fastsim.md,
    // "What it is", item 7).
    if (!eps_[kEtaDriveSlope].empty() && e2[0] > 0.0) {
      const double w = etaSlopeWeight(e2[0], e2[1], share[2]);
      if (w > 0.0) setEtaSlope(logRatioOf(kEtaDriveSlope) * w, a, &L);
    }
  }
  // One ratio for the step: the kinds' ratios averaged in ln with weights their shares of e^2 (a
  // single creepage gets its own curve exactly). The geometric mean fitted the combined exact
  // curves better than the arithmetic one (identify_calibration's combined rays;
  // doc/calibrated_fastsim.md, "What it is", item 2).
  const double logRho = finite
                            ? share[0] * logRatioOf(kXiRatio) +
                                  share[1] * towardsNoSpin(logRatioOf(kEtaRatio), kEtaRatioNoSpin) +
                                  share[2] * logRatioOf(kSpinRatio)
                            : logRatioOf(kXiRatio);
  const bool spin = finite && e2[2] > 0.0;
  const bool shaped = spin && !eps_[kSpinBoundShape].empty();  // from spin's share (23s)
  const double logShape = shaped ? logRatioOf(kSpinBoundShape) : 0.0;
  // The combined correction's ln multipliers, of L1, L2, L3, of the bound's shape and of L3x, in
  // one lookup; each goes into the exp of the ratio it multiplies. None for one kind or xi with
  // eta. The step's exps (inline): the ratios of L1, L2, L3 (the correction's multipliers folded
  // in), of the spin drive's L3x to L3 (below) and the bound's shape.
  double lm[kMultipliers], r1, r2, r3, shapeRatio = 0.0;
  const double rest = e2[0] + e2[1];
  const bool corrected = finite && !corrS3_.empty() && e2[2] > 0.0 && rest > 0.0;
  if (corrected && vectorised_) {
    // The first four multipliers and their exps in the lanes (correction_lanes.hpp), the fifth
    // (of L3x alone, its exp below) as the scalar path.
    const CorrectionCell cc = correctionCell(share[2], e2[0] / rest, e);
    fillCell(cc, opposed);
    const double base[4] = {logRho, logRho, logRho, logShape};
    double r[4];
    calibration::correctedExpsInLanes(cc.lo, cc.alongT, cc.alongS, cc.branch, cc.we, cc.wt, cc.ws,
                                      opposed, base, r);
    auto fifth = [&](const double* l0) {
      return inCell(l0, cc.alongT, cc.alongS, cc.we, cc.wt, cc.ws, kSpinDriveMultiplier);
    };
    lm[kSpinDriveMultiplier] =
        opposed <= 0.0   ? fifth(cc.lo)
        : opposed >= 1.0 ? fifth(cc.lo + cc.branch)
                         : (1.0 - opposed) * fifth(cc.lo) + opposed * fifth(cc.lo + cc.branch);
    r1 = r[0];
    r2 = r[1];
    r3 = r[2];
    shapeRatio = r[3];
  } else {
    if (corrected) lookUpCorrection(share[2], e2[0] / rest, e, opposed, 0, kMultipliers, lm);
    r1 = std::exp(corrected ? logRho + lm[0] : logRho);
    r2 = corrected ? std::exp(logRho + lm[1]) : r1;
    r3 = corrected ? std::exp(logRho + lm[2]) : r1;
    if (shaped) shapeRatio = std::exp(logShape + (corrected ? lm[3] : 0.0));
  }
  // Towards full slip the flexibilities blend into one, L_crss (Vollebregt and Voltr 2023,
  // CONTACT's FASTSIM): the saturated traction then points along the rigid slip, as in exact
  // theory, not along (xi / L1, eta / L2). A single creepage has L_crss = its own L, unchanged.
  // Weight min(1, e / kCrssFrom): of e / 1.5, 3, 5, 10, 20 the one nearest the combined exact
  // curves.
  // L_crss = (xi^2 + eta^2 + (k phi)^2) / (xi^2 / L1 + eta^2 / L2 + (k phi)^2 / L3), in one
  // division: numerator and denominator times L1 L2 L3.
  const double kphi = 3.0 * M_PI * a / 32.0 * c.phi, x2 = c.xi * c.xi, y2 = c.eta * c.eta,
               s2 = kphi * kphi, L23 = L.L2 * L.L3, L12 = L.L1 * L.L2;
  const double den = x2 * L23 + (y2 * L.L3 + s2 * L.L2) * L.L1;
  const double w = finite ? std::min(1.0, e / kCrssFrom) : 1.0;
  const double crss = den > 0.0 ? (x2 + y2 + s2) * (L12 * L.L3) / den : L.L1;
  L.L1 = r1 * ((1.0 - w) * L.L1 + w * crss);
  L.L2 = r2 * ((1.0 - w) * L.L2 + w * crss);
  L.L3 = r3 * ((1.0 - w) * L.L3 + w * crss);
  // Without spin (e3 = 0) both spin terms are exactly their classic values: no exp.
  // The correction's fifth multiplier (c3x) acts on L3x alone, in the same exp. 23x's knot 0 is
  // linear theory's spin moment (C33): it holds for the rest of e^2 too (spin's own curve has it
  // for spin's share) until the patch slips (linearSpinMoment).
  if (spin && (!eps_[kSpinDriveRatio].empty() || corrected)) {
    double lx = corrected ? lm[kSpinDriveMultiplier] : 0.0;
    if (!eps_[kSpinDriveRatio].empty())
      lx += share[2] * logRatioOf(kSpinDriveRatio) +
            (1.0 - share[2]) * logRatio_[kSpinDriveRatio][0] * linearSpinMoment(e);
    L.L3x = L.L3 * std::exp(lx);
  } else if (!eps_[kSpinDriveRatio].empty())
    L.L3x = L.L3;
  // The held coupling's moment on spin's lateral traction, in linear theory
  // -kappa phi a^4 b^3 32 / (315 L3) against the spin drive's -phi 8 a^2 b^3 / (15 L3x), is taken
  // back by a stiffer drive: 1 / L3x less kappa a^2 (4 / 21) / L3 (spinCouplingCompensation).
  if (spin && held > 0.0) {
    const double perL3x =
        1.0 / L.spinX() - held * spinCouplingCompensation(L.lateralCoupling, a, L.L3);
    if (perL3x > 0.0) L.L3x = 1.0 / perL3x;
  }
  // The bound's shape: shape_23s(e) times spin's share of e^2 and shape_22s(e) times eta's where
  // spin's is small (no friction: parabolic).
  const double etaShape = noSpin > 0.0 ? noSpin * share[1] * logRatioOf(kEtaBoundShapeNoSpin) : 0.0;
  if (shaped)
    s.boundShape = towardsFullSlip(std::min(kMaxBoundShape, shapeRatio * share[2] + etaShape), e,
                                   share[2], a / b);
  else
    s.boundShape = etaShape;
  return s;
}

double PatchCalibration::towardsFullSlip(double shape, double e, double s3, double aOverB) const {
  return corrS3_.empty() ? shape : hertzShapeBlend(shape, e, s3, aOverB);
}

double PatchCalibration::hertzShapeBlend(double shape, double e, double s3, double aOverB) {
  using namespace calibration;
  if (!(s3 > 0.0) || !(s3 < kSmallSpinShare)) return shape;
  const double from = fullSlipFrom(s3, aOverB);
  if (!(e > from)) return shape;
  const double q = std::min(1.0, (e - from) / (fullSlipTo(aOverB) - from));
  const double w = q * q * (3.0 - 2.0 * q) * (1.0 - s3 / kSmallSpinShare) *
                   std::min(1.0, s3 / kHertzShapeSpinShare);
  return shape + (kHertzMomentShape - shape) * w;
}

namespace {

[[noreturn]] void fail(const std::string& path, long line, const std::string& why) {
  throw std::runtime_error("calibration table " + path + ":" + std::to_string(line) + ": " + why);
}

double number(const std::string& path, long line, std::string_view s) {
  // from_chars: correctly rounded as strtod is in the C locale, with no locale to consult, and
  // several times faster over the shipped table's millions of numbers, read at start-up. What it
  // does not take whole (a sign '+', leading space, hex, a value out of its range) goes to strtod.
  double v = 0.0;
  const char* const last = s.data() + s.size();
  const std::from_chars_result fast = std::from_chars(s.data(), last, v);
  if (fast.ec == std::errc() && fast.ptr == last && std::isfinite(v)) return v;
  const std::string text(s);
  char* end = nullptr;
  v = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !std::isfinite(v))
    fail(path, line, "not a finite number: " + text);
  return v;
}

// The optional columns after a_over_b,kind,epsilon,ratio, found by their names in the header.
enum Column { kFitError, kFastsimNx, kSpinShare, kXiShare, kSign, kColumns };
const char* const kColumnNames[kColumns] = {"fit_error", "fastsim_nx", "spin_share", "xi_share",
                                            "sign"};

// Why a value of single kind `kind` is out of its range (calibration::KindInfo).
std::string rangeMessage(int kind) {
  const calibration::KindInfo& k = calibration::kKindInfo[kind];
  const std::string what = kind == calibration::kSpinBoundShape  ? "a bound shape"
                           : kind == calibration::kEtaDriveSlope ? "eta's drive's slope"
                                                                 : "eta's bound shape";
  char range[64];
  if (k.heldAsIs)
    std::snprintf(range, sizeof range, "[%g, %g]", k.min, k.max);
  else
    std::snprintf(range, sizeof range, "(0, %g]", k.max);
  return what + " (" + std::string(k.code) + ") must be in " + range;
}

// 1 / (x[i] - x[i - 1]) into w[i], w[0] = 0 (PatchCalibration's cell weights).
void reciprocalWidths(const std::vector<double>& x, std::vector<double>* w) {
  w->resize(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) (*w)[i] = i == 0 ? 0.0 : 1.0 / (x[i] - x[i - 1]);
}

}  // namespace

CalibrationTable CalibrationTable::parse(std::istream& in, const std::string& path) {
  CalibrationTable t;
  std::string line;
  long n = 0;
  bool header = false;
  int column[kColumns];
  std::fill(column, column + kColumns, -1);
  std::size_t nColumns = 0;
  // Combined correction rows per (mesh, a/b row, multiplier, opposed, spin share, xi share):
  // knots, ratios.
  using CorrKey = std::tuple<std::size_t, std::size_t, int, int, double, double>;
  std::map<CorrKey, std::pair<std::vector<double>, std::vector<double>>> corr;
  // A direction's knots come row after row: the last one's entry is kept (the shipped table is
  // some 640 000 such rows, parsed at start-up).
  CorrKey lastKey;
  std::pair<std::vector<double>, std::vector<double>>* last = nullptr;
  std::vector<std::string_view> f;  // the line's fields, views into it
  while (std::getline(in, line)) {
    ++n;
    if (line.empty() || line[0] == '#') continue;
    splitCsvFields(line, &f);
    if (!header) {
      if (f.size() < 4 || f[0] != "a_over_b" || f[1] != "kind" || f[2] != "epsilon" ||
          f[3] != "ratio")
        fail(path, n, "expected header a_over_b,kind,epsilon,ratio");
      for (std::size_t i = 4; i < f.size(); ++i) {
        const auto name = std::find(kColumnNames, kColumnNames + kColumns, f[i]);
        if (name == kColumnNames + kColumns)
          fail(path, n,
               "unknown column '" + std::string(f[i]) +
                   "' (fit_error, fastsim_nx, spin_share, xi_share, sign)");
        int& c = column[name - kColumnNames];
        if (c >= 0) fail(path, n, "column '" + std::string(f[i]) + "' repeated");
        c = static_cast<int>(i);
      }
      nColumns = f.size();
      header = true;
      continue;
    }
    if (f.size() < 4) fail(path, n, "expected a_over_b,kind,epsilon,ratio");
    if (f.size() > nColumns) fail(path, n, "more fields than the header has columns");
    auto given = [&](Column c) {
      return column[c] >= 0 && static_cast<std::size_t>(column[c]) < f.size() &&
             !f[column[c]].empty();
    };
    int nx = 0;
    if (column[kFastsimNx] >= 0) {
      if (!given(kFastsimNx)) fail(path, n, "fastsim_nx missing");
      const double v = number(path, n, f[column[kFastsimNx]]);
      if (!(v >= 2.0 && v <= 100000.0) || v != std::floor(v))
        fail(path, n, "fastsim_nx must be an integer >= 2");
      nx = static_cast<int>(v);
    }
    if (t.meshes_.empty() || t.meshes_.back().nx != nx) {
      for (const Mesh& m : t.meshes_)
        if (m.nx == nx)
          fail(path, n, "fastsim_nx " + std::to_string(nx) + ": each mesh's rows in one block");
      t.meshes_.push_back(Mesh{nx, {}});
    }
    std::vector<Row>& rows = t.meshes_.back().rows;
    const double ab = number(path, n, f[0]), e = number(path, n, f[2]), r = number(path, n, f[3]);
    // The kind by its code or name (calibration_schema.hpp): a single kind, or (multiplier >= 0)
    // one of the combined correction's.
    int kind = -1, multiplier = -1;
    for (int k = 0; k < calibration::kKinds && kind < 0; ++k)
      if (f[1] == calibration::kKindInfo[k].code || f[1] == calibration::kKindInfo[k].name)
        kind = k;
    for (int p = 0; p < calibration::kMultipliers && kind < 0 && multiplier < 0; ++p)
      if (f[1] == calibration::kMultiplierInfo[p].code ||
          f[1] == calibration::kMultiplierInfo[p].name)
        multiplier = p;
    if (kind < 0 && multiplier < 0)
      fail(path, n,
           "kind must be 11, 22, 23, 23x, 23s, 22c, 22b, 22n, 22cn, 22s, c1, c2, c3, cs or c3x, "
           "got '" +
               std::string(f[1]) + "'");
    const calibration::KindInfo& info =
        kind >= 0 ? calibration::kKindInfo[kind] : calibration::kMultiplierInfo[multiplier];
    if (!(ab > 0.0)) fail(path, n, "a_over_b must be > 0");
    if (!(r > 0.0) && !info.heldAsIs) fail(path, n, "ratio must be > 0");
    const double logAB = std::log(ab);
    if (rows.empty() || rows.back().logAB != logAB) {
      if (!rows.empty() && !(logAB > rows.back().logAB))
        fail(path, n, "a_over_b must increase from one block to the next");
      rows.push_back(Row{ab, logAB, {}, {}, {}, {}, {}});  // corr: its default, empty
    }
    if (multiplier >= 0) {
      if (!given(kSpinShare) || !given(kXiShare) || !given(kSign))
        fail(path, n, "a c-kind row needs spin_share, xi_share and sign");
      const double s3 = number(path, n, f[column[kSpinShare]]),
                   xs = number(path, n, f[column[kXiShare]]),
                   sg = number(path, n, f[column[kSign]]);
      if (!(s3 > 0.0 && s3 < 1.0)) fail(path, n, "spin_share must be in (0, 1)");
      if (!(xs >= 0.0 && xs <= 1.0)) fail(path, n, "xi_share must be in [0, 1]");
      if (sg != 1.0 && sg != -1.0) fail(path, n, "sign must be 1 or -1");
      const CorrKey key{
          t.meshes_.size() - 1, rows.size() - 1, multiplier, sg < 0.0 ? 1 : 0, s3, xs};
      if (last == nullptr || key != lastKey) last = &corr[key], lastKey = key;
      auto& knots = *last;
      if (knots.first.empty() ? (e != 0.0 || r != 1.0) : !(e > knots.first.back()))
        fail(path, n, "the knots of a kind start at epsilon 0, ratio 1 and increase");
      knots.first.push_back(e);
      knots.second.push_back(r);
      continue;
    }
    Row& row = rows.back();
    std::vector<double>& x = row.eps[kind];
    if (!(r >= info.min && r <= info.max)) fail(path, n, rangeMessage(kind));
    // 23s, 22c, 22b, 22cn and 22s take any value at knot 0 (a shape, a coupling, a slope: not
    // ratios to Kalker's), and 23x its linear value (L3x over L3 for exact theory's linear spin
    // moment, C33).
    if (x.empty() ? (e != 0.0 || (info.oneAtZero && r != 1.0)) : !(e > x.back()))
      fail(path, n, "the knots of a kind start at epsilon 0, ratio 1 and increase");
    x.push_back(e);
    row.ratio[kind].push_back(r);
  }
  if (!header) fail(path, n, "no header");
  for (std::size_t m = 0; m < t.meshes_.size(); ++m) {
    std::vector<Row>& rows = t.meshes_[m].rows;
    const std::string mesh = t.meshes_[m].nx > 0
                                 ? " (fastsim_nx " + std::to_string(t.meshes_[m].nx) + ")"
                                 : std::string();
    for (const Row& row : rows)
      for (int k = 0; k < calibration::kKinds; ++k)
        if ((k < 3 && row.eps[k].empty()) || row.eps[k] != rows.front().eps[k])
          fail(path, n, "every a/b must hold every kind, with the same epsilon knots" + mesh);
    // Eta without spin replaces the pair 22, 22c: its three kinds together, and with 22c.
    {
      namespace F = calibration;
      const Row& row = rows.front();
      const bool any = !row.eps[F::kEtaRatioNoSpin].empty() ||
                       !row.eps[F::kEtaCouplingNoSpin].empty() ||
                       !row.eps[F::kEtaBoundShapeNoSpin].empty();
      if (any && (row.eps[F::kEtaRatioNoSpin].empty() || row.eps[F::kEtaCouplingNoSpin].empty() ||
                  row.eps[F::kEtaBoundShapeNoSpin].empty() || row.eps[F::kEtaCoupling].empty()))
        fail(path, n, "22n, 22cn and 22s come together, with 22c" + mesh);
    }
    // The combined correction: a full grid (every multiplier, sign, spin share and xi share) with
    // the same knots in every a/b, or none.
    // c3x (the multiplier of L3x alone) is optional: in every direction or in none (then 1).
    bool withC3x = false;
    for (const auto& [key, knots] : corr) {
      if (std::get<0>(key) != m) continue;
      withC3x = withC3x || std::get<2>(key) == 4;
      Row& row = rows[std::get<1>(key)];
      auto add = [](std::vector<double>* v, double x) {
        if (std::find(v->begin(), v->end(), x) == v->end())
          v->insert(std::upper_bound(v->begin(), v->end(), x), x);
      };
      add(&row.corrS3, std::get<4>(key));
      add(&row.corrT, std::get<5>(key));
      if (row.corrEps.empty()) row.corrEps = knots.first;
      if (knots.first != row.corrEps || knots.first.size() < 2)
        fail(path, n,
             "every combined correction must hold the same epsilon knots (at least two)" + mesh);
    }
    for (std::size_t r = 0; r < rows.size(); ++r) {
      Row& row = rows[r];
      const Row& first = rows.front();
      if (row.corrS3 != first.corrS3 || row.corrT != first.corrT || row.corrEps != first.corrEps)
        fail(path, n, "every a/b must hold the same combined correction grid" + mesh);
      if (row.corrS3.empty()) continue;
      if (row.corrT.size() < 2 || row.corrT.front() != 0.0 || row.corrT.back() != 1.0)
        fail(path, n, "the combined correction's xi shares must run from 0 to 1" + mesh);
      const std::size_t nS = row.corrS3.size(), nT = row.corrT.size(), nE = row.corrEps.size();
      auto multipliers =
          std::make_shared<std::vector<double>>(calibration::kMultipliers * 2 * nS * nT * nE, 1.0);
      for (int p = 0; p < calibration::kMultipliers; ++p)
        for (int o = 0; o < 2; ++o)
          for (std::size_t i = 0; i < nS; ++i)
            for (std::size_t j = 0; j < nT; ++j) {
              const auto it = corr.find({m, r, p, o, row.corrS3[i], row.corrT[j]});
              if (it == corr.end() && p == 4 && !withC3x) continue;
              if (it == corr.end())
                fail(path, n,
                     "the combined correction misses a direction (every c1, c2, c3, cs, sign, "
                     "spin share and xi share; c3x in every one or none)" +
                         mesh);
              std::copy(it->second.second.begin(), it->second.second.end(),
                        multipliers->begin() + (((p * 2 + o) * nS + i) * nT + j) * nE);
            }
      row.corr = std::move(multipliers);
    }
  }
  sortByNodes(&t.meshes_);
  return t;
}

bool CalibrationTable::sameKnots(const std::vector<Row>& x, const std::vector<Row>& y) {
  if (x.size() != y.size()) return false;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const Row &p = x[i], &q = y[i];
    if (p.logAB != q.logAB || p.corrS3 != q.corrS3 || p.corrT != q.corrT ||
        p.corrEps != q.corrEps || p.corr->size() != q.corr->size())
      return false;
    for (int k = 0; k < calibration::kKinds; ++k)
      if (p.eps[k] != q.eps[k] || p.ratio[k].size() != q.ratio[k].size()) return false;
  }
  return true;
}

CalibrationTable CalibrationTable::forMesh(int nx) const {
  if (meshes_.size() <= 1) return *this;
  CalibrationTable t;
  // Between two identified meshes the ratios are interpolated in 1/nx (ln ratio; the coupling
  // itself), where both hold the same knots; on an identified mesh, beyond the table's meshes or
  // between tables of other knots, the nearest mesh.
  const Mesh *lo = nullptr, *hi = nullptr;
  double w = 0.0;
  if (!meshesAround(meshes_, nx, &lo, &hi, &w) || !sameKnots(rowsOf(*lo), rowsOf(*hi))) {
    const Mesh& m = nearestMesh(meshes_, nx);
    t.meshes_.push_back(Mesh{m.nx, rowsOf(m)});
    return t;
  }
  auto blend = [w](double x, double y) {
    return std::exp((1.0 - w) * std::log(x) + w * std::log(y));
  };
  Mesh m{nx, rowsOf(*lo)};
  const std::vector<Row>& high = rowsOf(*hi);
  for (std::size_t r = 0; r < m.rows.size(); ++r) {
    Row& row = m.rows[r];
    const Row& h = high[r];
    for (int k = 0; k < calibration::kKinds; ++k)
      for (std::size_t j = 0; j < row.ratio[k].size(); ++j)
        row.ratio[k][j] = calibration::kKindInfo[k].heldAsIs
                              ? row.ratio[k][j] + w * (h.ratio[k][j] - row.ratio[k][j])
                              : blend(row.ratio[k][j], h.ratio[k][j]);
    auto corr = std::make_shared<std::vector<double>>(*row.corr);
    for (std::size_t j = 0; j < corr->size(); ++j) (*corr)[j] = blend((*corr)[j], (*h.corr)[j]);
    row.corr = std::move(corr);
  }
  t.meshes_.push_back(std::move(m));
  return t;
}

std::vector<int> CalibrationTable::meshes() const {
  return nodeCounts(meshes_);
}

PatchCalibration CalibrationTable::at(double a_over_b) const {
  PatchCalibration c;
  at(a_over_b, &c);
  c.fillCorrection();
  return c;
}

void CalibrationTable::at(double a_over_b, PatchCalibration* c) const {
  if (meshes_.empty()) {
    *c = PatchCalibration();
    return;
  }
  if (meshes_.size() != 1)
    throw std::logic_error("CalibrationTable: a table of " + std::to_string(meshes_.size()) +
                           " FastSim meshes: narrow it with forMesh() first");
  const std::vector<Row>& rows = rowsOf(meshes_.front());
  const double x = std::log(a_over_b);
  std::size_t i = 0;
  while (i + 1 < rows.size() && rows[i + 1].logAB <= x) ++i;
  const Row& lo = rows[i];
  const Row& hi = rows[std::min(i + 1, rows.size() - 1)];
  const double t =
      (&lo == &hi || !(x > lo.logAB)) ? 0.0 : std::min(1.0, (x - lo.logAB) / (hi.logAB - lo.logAB));
  // The knots and what follows from them alone (the cells' widths, where searches start) stay
  // as they are where c holds this table's already (a model re-picking its a/b).
  bool knotsHeld = c->corrS3_ == lo.corrS3 && c->corrT_ == lo.corrT && c->corrEps_ == lo.corrEps;
  for (int k = 0; k < calibration::kKinds && knotsHeld; ++k) knotsHeld = c->eps_[k] == lo.eps[k];
  for (int k = 0; k < calibration::kKinds; ++k) {
    c->logRatio_[k].resize(lo.ratio[k].size());
    for (std::size_t j = 0; j < lo.ratio[k].size(); ++j) {
      const double v = lo.ratio[k][j] + t * (hi.ratio[k][j] - lo.ratio[k][j]);
      c->logRatio_[k][j] = calibration::kKindInfo[k].heldAsIs ? v : std::log(v);
    }
  }
  const std::size_t nS = lo.corrS3.size(), nT = lo.corrT.size(), nE = lo.corrEps.size();
  constexpr int P = calibration::kMultipliers;
  if (!knotsHeld) {
    for (int k = 0; k < calibration::kKinds; ++k) {
      c->eps_[k] = lo.eps[k];  // every row has the same knots: the storage c holds is reused
      reciprocalWidths(c->eps_[k], &c->perWidth_[k]);
    }
    c->sharedKnots_ = true;
    for (int k = 1; k < calibration::kKinds; ++k)
      if (!c->eps_[k].empty() && c->eps_[k] != c->eps_[0]) c->sharedKnots_ = false;
    c->corrS3_ = lo.corrS3;
    c->corrT_ = lo.corrT;
    c->corrEps_ = lo.corrEps;
    // Spin-share cells with the implicit ends 0 and 1: knots 0, corrS3..., 1.
    c->corrS3PerWidth_.resize(nS == 0 ? 0 : nS + 1);
    for (std::size_t q = 0; q < c->corrS3PerWidth_.size(); ++q)
      c->corrS3PerWidth_[q] =
          1.0 / ((q == nS ? 1.0 : lo.corrS3[q]) - (q == 0 ? 0.0 : lo.corrS3[q - 1]));
    reciprocalWidths(c->corrT_, &c->corrTPerWidth_);
    reciprocalWidths(c->corrEps_, &c->corrEpsPerWidth_);
    c->setSearchStarts();
    // Grid point by grid point (the end rows 0, never filled), none filled yet.
    c->corrLog_.assign(nS == 0 ? 0 : 2 * (nS + 2) * nT * nE * P, 0.0);
    c->corrFilledAt_.assign(c->corrLog_.size() / P, 0);
    c->corrPick_ = 0;
  }
  c->vectorised_ = stripLanesAvailable();
  // A new pick: every grid point's values are stale until fillGridPoint computes them.
  if (++c->corrPick_ == 0) {
    std::fill(c->corrFilledAt_.begin(), c->corrFilledAt_.end(), 0);
    c->corrPick_ = 1;
  }
  c->corrLo_ = lo.corr;
  c->corrHi_ = hi.corr;
  c->corrWeight_ = t;
}

void PatchCalibration::fillGridPoint(std::size_t g) const {
  // g = ((opposed * (nS + 2) + i) * nT + j) * nE + k; rows i = 0 and nS + 1 are the ends (0).
  const std::size_t nS = corrS3_.size(), nT = corrT_.size(), nE = corrEps_.size();
  const std::size_t k = g % nE, j = (g / nE) % nT, i = (g / (nE * nT)) % (nS + 2),
                    o = g / (nE * nT * (nS + 2));
  corrFilledAt_[g] = corrPick_;
  if (i == 0 || i == nS + 1) return;
  // From the table's layout ((((p * 2 + o) * nS + q) * nT + j) * nE + k), q = i - 1.
  constexpr int P = calibration::kMultipliers;
  const std::vector<double>& lo = *corrLo_;
  const std::vector<double>& hi = *corrHi_;
  const double t = corrWeight_;
  for (int p = 0; p < P; ++p) {
    const std::size_t from = (((p * 2 + o) * nS + i - 1) * nT + j) * nE + k;
    corrLog_[g * P + p] = std::log(lo[from] + t * (hi[from] - lo[from]));
  }
}

void PatchCalibration::fillCorrection() const {
  for (std::size_t g = 0; g < corrFilledAt_.size(); ++g)
    if (corrFilledAt_[g] != corrPick_) fillGridPoint(g);
}

}  // namespace wheel_rail_contact
