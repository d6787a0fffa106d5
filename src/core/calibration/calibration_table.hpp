/// Calibrated FastSim (issue 19): Kalker's flexibilities scaled, per creepage kind, by a ratio that
/// depends on how far the contact is from linear theory, the ratio identified against our exact
/// half-space solver (src/tools/identify_calibration.cpp) so that FastSim's steady creep curves
/// follow the exact ones. The ratio is 1 at zero creepage, so linear theory (Kalker's coefficients)
/// stays exact, and it is chosen once per step from that step's creepages and load: the march then
/// runs unchanged with the scaled flexibilities, on a traction field bounded by mu p; the time term
/// marches that field as it always does (its history is traction, which a change of flexibility
/// between steps leaves standing, like the drive's change with the creepage).
///
/// Normalised creepage: each kind's linear force over mu fz,
///   e1 = G a b C11 |xi| / (mu fz), e2 = G a b C22 |eta| / (mu fz), e3 = G (ab)^1.5 C23 |phi| / (mu
///   fz),
/// and e = sqrt(e1^2 + e2^2 + e3^2). The step's flexibilities are
///   L_i = rho(e) ((1 - w) L_i,Kalker + w L_crss),   ln rho = sum_k e_k^2 ln ratio_k(e) / e^2,
/// w = min(1, e / 5), L_crss = (xi^2 + eta^2 + (k phi)^2) / (xi^2/L1 + eta^2/L2 + (k phi)^2/L3),
/// k = 3 pi a / 32 (CONTACT's FASTSIM, Vollebregt and Voltr 2023): a single
/// creepage of kind k gets L_k ratio_k(e) exactly, so the table is identified on single creepages.
/// Spin has a second parameter: the flexibility of its longitudinal drive (-phi y / L3x,
/// Flexibilities::L3x) is L3x = L3 ratio_23x(e)^(e3^2 / e^2) ratio_23x(0)^((1 - e3^2 / e^2) w(e)),
/// w = linearSpinMoment(e). Near linear theory spin's moment comes from that drive alone,
/// phi 8 a^2 b^3 / (15 L3x), so L3x = L3 misses C33 (by 2-64 % of the exact moment at a/b 0.2-5);
/// 23x's knot 0 is the ratio that gives exact theory's, and it holds whatever spin's share until
/// the patch slips (w = 1 up to e = 2, 0 from e = 4.5). One flexibility ratio moves the
/// spin curve along e only, and FastSim's pure-spin Fy peaks higher than the exact one and its Mz
/// runs low; a stiffer longitudinal spin drive saturates the patch earlier and carries more of the
/// moment, so the pair (ratio_23, ratio_23x) fits Fy and Mz together. Optional in the table
/// (absent: 1, Kalker's L3). With it goes the bound's shape (flattenedBound): the parabolic
/// bound's spin moment at full slip is 10 % below the exact one whatever the flexibilities, so spin
/// saturates on a flatter bound, s = shape_23s(e) e3^2 / e^2: no spin, the parabolic bound of
/// classic FastSim; kind 23s holds the shape per a/b identified for pure spin, in (0, 1],
/// interpolated linearly.
///
/// Combined creepages (kinds c1, c2, c3, optional): the rule above is exact for one kind and
/// weakest where spin combines with xi or eta, so the step's L1, L2, L3 (L3x with L3) are
/// multiplied by a correction tabulated over the creepage's direction and e: spin's share
/// s3 = e3^2 / e^2 on interior knots (the correction is 1 at s3 = 0 and 1, where the rule is
/// already fitted), xi's share of the rest t = e1^2 / (e1^2 + e2^2) on knots from 0 to 1, and the
/// relative sign of eta and phi ((xi, eta, phi) and (-xi, eta, phi) are mirror images: only
/// sign(eta phi) matters). ln multiplier interpolated bilinearly in (s3, t), linearly in e. The
/// fourth (kind cs) multiplies the bound's shape: in full slip the flexibilities hardly act, and
/// the bound's shape decides how the saturated traction splits into force and moment. The fifth
/// (kind c3x, optional: 1 where the table has none) multiplies L3x besides L3's: where xi drives
/// most of the patch and spin some 40 %, on a long patch, spin's longitudinal drive and its lateral
/// one share the moment otherwise than under pure spin, and four multipliers could not fit force
/// and moment together (doc/calibrated_fastsim.md, "What it is", item 5).
///
/// The moment from eta (kind 22c, optional: none is Kalker's FastSim's u = L tau): exact theory
/// keeps a spin moment from lateral creepage into full slip, decaying as 1 / e, which FastSim
/// cannot make (without spin its saturated traction has one direction over the patch). It comes
/// from Poisson's ratio: lateral traction displaces the surface longitudinally, oddly in y, and
/// rolling turns that into longitudinal slip. The table's coupling c(e) (dimensionless, per a/b,
/// interpolated linearly in e and a/b, held beyond the last knot) adds (c / G)(y / b) tau_y to the
/// longitudinal slip, i.e. lateralCoupling = c / (G b L1,Kalker) to the x drive
/// (Flexibilities::lateralCoupling); identified with 22's ratio on eta alone against Fy and Mz.
/// Odd in y, it leaves every force of linear theory as it was.
///
/// The moment of xi with eta (kind 22b, optional: none is a uniform drive): with xi beside eta,
/// on a wide patch (a/b 0.2) and a long one (a/b 5), the exact moment falls off otherwise than
/// FastSim's as the patch saturates, which the coupling identified on eta alone cannot follow. The
/// table's slope beta(e) (per a/b, interpolated linearly in e and a/b) makes eta's drive
/// (eta / L2)(1 - beta x / a) / (1 - 3 pi beta / 32) (Flexibilities::etaSlope, etaGain; the same
/// lateral force in linear theory): the saturated traction turns along the strip and carries a
/// moment. Identified on xi = eta after 11, 22 and 22c (and again with eta's set without spin,
/// below, where the table has it), applied with etaSlopeWeight (full at xi = eta, none on one
/// creepage). In the march it folds into spin's lateral drive, which is
/// already linear in x: no work per node.
///
/// Eta without spin (kinds 22n, 22cn, 22s, optional): on a long patch (a/b 5) eta's ratio and
/// coupling cannot fit Fy and Mz together, nor then xi = eta's moment. Where spin has no share they
/// are replaced by eta's own set, fitted with a bound shape for eta (22s, applied times eta's share
/// of e^2) and 22b's slope against eta alone and xi = eta together: ratio_22n (a ratio, 1 at knot
/// 0) and coupling c_n. The step takes ln ratio_22 + n (ln ratio_22n - ln ratio_22) and
/// c + n (c_n - c), n = noSpinWeight(s3), 1 without spin falling linearly to 0 at kNoSpinTo: from
/// there on (and on spin alone, whose parameters were fitted on c) the pair fitted on eta alone,
/// on which the combined correction is identified, holds as it was.
///
/// Table (CSV, '#' comment lines: command, Poisson ratio, grids, fit errors):
///   a_over_b,kind,epsilon,ratio[,...]   optional columns, named in the header, in any order:
///   fit_error, fastsim_nx, spin_share, xi_share, sign (an empty or missing field: not given)
///   kind: a code or name of calibration_schema.hpp's kKindInfo and kMultiplierInfo (what each
///   is, and its range); c-kinds carry their direction (sign +1 or -1); 22c's and 22cn's "ratio"
///   is the coupling c, 22b's the slope beta, 22s's the shape
/// fastsim_nx: the FastSim mesh's nodes per strip the row was identified on (FastSim's own
/// discretisation error differs per mesh, the exact curves do not); each mesh's rows in one block.
/// A table without the column is one mesh that serves every nx.
/// Every a/b holds the same epsilon knots per kind (increasing, the first 0; there 11, 22 and 23
/// have ratio 1); ln ratio is interpolated linearly in epsilon and held beyond the last knot; the
/// ratio linearly in ln(a/b) between rows, clamped at the table's ends. The table is identified at
/// nu = 0.28: at another nu the same ratios apply to that nu's Kalker flexibilities (the
/// normalisation by C_ij(nu) carries the first-order effect of nu).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iosfwd>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "core/calibration/calibration_schema.hpp"
#include "core/fastsim/fastsim.hpp"

namespace wheel_rail_contact {

/// One step's calibrated parameters: the march's flexibilities and the bound's shape.
struct CalibratedStep {
  Flexibilities L;
  double boundShape = 0.0;  // flattenedBound's shape; 0: the parabolic bound
};

/// The three ratio curves at one a/b; empty (the default) is classic FastSim: every ratio 1.
class PatchCalibration {
 public:
  bool classic() const { return eps_[0].empty(); }
  /// Whether step() interpolates the combined correction and takes its exps four at a time in the
  /// lanes of a vector register, where the CPU has them (the default, as the marches':
  /// stripLanesAvailable); the results are the scalar path's within 1e-12 relative
  /// (correction_lanes.hpp; tests compare the two).
  void setVectorised(bool on) { vectorised_ = on && stripLanesAvailable(); }
  bool vectorised() const { return vectorised_; }
  /// The step's flexibilities and bound shape together (what flexibilities() and boundShape()
  /// give), from one normalised creepage, one knot search and one correction lookup: what a
  /// model calls each step. Classic: Kalker's flexibilities and shape 0.
  CalibratedStep step(double a, double b, double G, const CreepCoefficients& k, double muFz,
                      const Creepages& c) const;
  /// The same with the correction's two branches (eta phi > 0 and eta phi < 0, identified apart)
  /// blended: `opposed` in [0, 1] is the weight of the eta phi < 0 branch (step() above: 1 where
  /// eta phi < 0, else 0). A model rolling through a reversal sees eta change sign at once in its
  /// forward frame (rolling_direction.hpp) and moves this weight over travel instead.
  CalibratedStep step(double a, double b, double G, const CreepCoefficients& k, double muFz,
                      const Creepages& c, double opposed) const;
  /// The eta phi < 0 branch's weight that creepages c select by themselves: 1 where eta phi < 0,
  /// else 0 (where eta phi = 0 both branches give the same correction's ends).
  static double opposedBranch(const Creepages& c) { return c.eta * c.phi < 0.0 ? 1.0 : 0.0; }
  /// That weight after `travel` [m] of rolling under creepages c, from `weight` (< 0: none yet):
  /// it relaxes towards opposedBranch(c) over the length `relaxation` [m], exp(-travel /
  /// relaxation), and is the target once within 1e-12 of it. A weight not yet set, or travel < 0,
  /// starts at the target; where eta phi = 0 the branches meet and the weight is kept.
  static double followedBranch(double weight, const Creepages& c, double travel,
                               double relaxation) {
    const double target = opposedBranch(c);
    if (weight < 0.0 || travel < 0.0) return target;
    if (c.eta * c.phi == 0.0 || weight == target) return weight;
    const double w = target + (weight - target) * std::exp(-travel / relaxation);
    return std::abs(w - target) < 1e-12 ? target : w;
  }
  /// Kalker's flexibilities at patch (a, b), scaled for creepages c at mu fz = muFz. Classic:
  /// exactly kalkerFlexibilities(a, b, G, k).
  Flexibilities flexibilities(double a, double b, double G, const CreepCoefficients& k, double muFz,
                              const Creepages& c) const;
  /// The bound's shape for this step (flattenedBound): shape_23s(e) times spin's share
  /// of e^2, e3^2 / e^2, and shape_22s(e) times eta's where spin's is small (noSpinWeight), where
  /// the table has them, else 0 (parabolic, as classic).
  double boundShape(double a, double b, double G, const CreepCoefficients& k, double muFz,
                    const Creepages& c) const;
  /// The combined correction's multipliers m[first..last) (0-2: of L1, L2, L3; 3: of the bound's
  /// shape; 4: of L3x besides L3's) for creepages with squares e2 (e1^2, e2^2, e3^2), e = their
  /// root sum, and eta phi < 0 (`opposed`); 1 where the table has none.
  void correction(const double* e2, double e, bool opposed, int first, int last, double* m) const;
  /// The bound's shape for combined creepages with a small spin share s3 = e3^2 / e^2, below
  /// kSmallSpinShare, on a patch of a/b = aOverB: the table's `shape` at normalised creepage e
  /// blended towards kHertzMomentShape as the patch goes into full slip (smoothly over e from
  /// fullSlipFrom(s3, aOverB) to fullSlipTo(aOverB)), by (1 - s3 / kSmallSpinShare)
  /// min(1, s3 / kHertzShapeSpinShare). In full slip the traction is mu p along the rigid slip,
  /// which spin turns over the patch: force and moment are the pressure's weighted sums of that
  /// direction field, right only with Hertz's weights. From kSmallSpinShare on the identified
  /// correction decides; without a correction (or spin), `shape` is returned. The shipped table's
  /// spin-share knots below kSmallSpinShare are identified with it in the fit and, near linear
  /// theory, hold the correction interpolated between no spin and the first knot from it on
  /// (identify_calibration).
  double towardsFullSlip(double shape, double e, double s3, double aOverB) const;
  /// towardsFullSlip's blend itself, whatever the table (identify_calibration fits a knot below
  /// kSmallSpinShare with it).
  static double hertzShapeBlend(double shape, double e, double s3, double aOverB);
  /// Normalised creepage from which towardsFullSlip moves the shape: kFullSlipFrom, and
  /// heldFullSlipFrom(aOverB) where the lateral coupling is held (heldShare): the held coupling's
  /// moment fades as the patch slips, and the full-slip shape has to take it over that much sooner
  /// for the small spin shares' moment to stay on the exact curves (doc/calibrated_fastsim.md,
  /// "What it is", items 6 and 8).
  static double fullSlipFrom(double s3, double aOverB) {
    using namespace calibration;
    return kFullSlipFrom + (heldFullSlipFrom(aOverB) - kFullSlipFrom) * heldShare(s3);
  }
  /// kHeldFullSlipFrom, and kWideHeldFullSlipFrom on a wide patch (wideness).
  static double heldFullSlipFrom(double aOverB) {
    using namespace calibration;
    return kHeldFullSlipFrom + (kWideHeldFullSlipFrom - kHeldFullSlipFrom) * wideness(aOverB);
  }
  /// Normalised creepage from which towardsFullSlip gives its full blend: kFullSlipTo, and
  /// kWideFullSlipTo on a wide patch (wideness).
  static double fullSlipTo(double aOverB) {
    using namespace calibration;
    return kFullSlipTo + (kWideFullSlipTo - kFullSlipTo) * wideness(aOverB);
  }
  /// How wide (b over a) the patch is, for the blend's span: 1 up to a/b = kWideTo, 0 from
  /// kNarrowFrom, linear in a/b between. On a patch five times as wide as long, spin turns the
  /// rigid slip over the patch's width (phi b) far more than its share of e (phi sqrt(ab)) says,
  /// and the full-slip shape has to take the small shares' moment over sooner: from e = 0.75 to
  /// 3.5 there (doc/calibrated_fastsim.md, "What it is", item 8).
  static double wideness(double aOverB) {
    using namespace calibration;
    return std::clamp((kNarrowFrom - aOverB) / (kNarrowFrom - kWideTo), 0.0, 1.0);
  }
  /// Ratio of kind k (calibration::Kind, a ratio: kXiRatio to kSpinBoundShape, kEtaRatioNoSpin)
  /// at normalised creepage e, and its logarithm (a kind held as is: its value, for logRatio).
  double ratio(int kind, double e) const;
  double logRatio(int kind, double e) const;
  /// The table's coupling c at normalised creepage e (22c; 0 where the table has none).
  double coupling(double e) const;
  /// The table's slope beta of eta's drive at normalised creepage e (22b; 0 where the table has
  /// none).
  double etaSlope(double e) const;
  /// The weight of the no-spin kinds (22n, 22cn, 22s) and of 22b's slope at spin's share s3 of
  /// e^2: 1 without spin, falling linearly to 0 at kNoSpinTo, the shipped table's first spin-share
  /// knot: from there on the combined correction, identified on the pair 22, 22c without the
  /// slope, decides.
  static double noSpinWeight(double s3) { return std::max(0.0, 1.0 - s3 / calibration::kNoSpinTo); }
  /// The weight of 22b's slope on creepages with squares e1^2, e2^2 and spin's share s3 of e^2:
  /// 4 t (1 - t), t xi's share of e1^2 + e2^2 (identified on xi = eta, t = 1/2; on eta alone the
  /// coupling carries the moment, and without eta the drive is zero), falling linearly with spin's
  /// share as noSpinWeight.
  static double etaSlopeWeight(double e1Sq, double e2Sq, double s3) {
    const double rest = e1Sq + e2Sq;
    return rest > 0.0 ? 4.0 * e1Sq * e2Sq / (rest * rest) * noSpinWeight(s3) : 0.0;
  }
  /// Flexibilities::etaSlope [1/m] and etaGain of slope beta on a patch of semi-axis a [m]: the
  /// drive (1 - beta x / a) / (1 - 3 pi beta / 32), whose linear-theory lateral force over the
  /// elliptic patch is the uniform drive's (the strips' sum of 2 a_j^2 (1 - (beta / 3) a_j / a)).
  /// beta is clamped to [-kMaxEtaSlope, kMaxEtaSlope] (the gain stays finite and positive).
  static void setEtaSlope(double beta, double a, Flexibilities* L) {
    beta = std::clamp(beta, -calibration::kMaxEtaSlope, calibration::kMaxEtaSlope);
    L->etaSlope = beta / a;
    L->etaGain = 1.0 / (1.0 - calibration::kEtaSlopeForce * beta);
  }
  /// Flexibilities::lateralCoupling [1/m^2] of coupling c at patch (a, b): c / (G b L1,Kalker) =
  /// 3 C11 c / (8 a b).
  static double lateralCoupling(double c, double a, double b, const CreepCoefficients& k) {
    return 3.0 * k.c11 * c / (8.0 * a * b);
  }
  /// The weight of 23x's knot 0 (linear theory's spin moment) on the share of e^2 that is not
  /// spin's: 1 up to kLinearSpinMomentTo, falling linearly to 0 at kLinearSpinMomentEnd. Through
  /// partial slip it keeps spin's moment where spin is a small share; in full slip the combined
  /// correction carries the moment, as it was fitted to (kept to e = 4.5 rather than 1 or 3: so
  /// the held-out directions' moment fits best; doc/calibrated_fastsim.md, "What it is", item 4).
  static double linearSpinMoment(double e) {
    using namespace calibration;
    return std::clamp((kLinearSpinMomentEnd - e) / (kLinearSpinMomentEnd - kLinearSpinMomentTo),
                      0.0, 1.0);
  }
  /// The share of the lateral coupling held where spin is a small share s3 = e3^2 / e^2 of the
  /// creepage, beyond the (e2^2 / (e2^2 + e3^2))^6 that spin's own parameters were identified
  /// with: 1 - e / kLinearSpinMomentEnd (0 beyond), times 1 up to s3 = kHeldCouplingFrom falling
  /// linearly to 0 at kHeldCouplingTo. There the moment is mostly eta's (its coupling), which the
  /// sixth power faded, leaving linear theory's moment off there (doc/calibrated_fastsim.md,
  /// "What it is", item 6).
  static double heldCoupling(double e, double s3) {
    return std::max(0.0, 1.0 - e / calibration::kLinearSpinMomentEnd) * heldShare(s3);
  }
  /// heldCoupling's factor of spin's share s3: 1 up to kHeldCouplingFrom, 0 from kHeldCouplingTo.
  static double heldShare(double s3) {
    using namespace calibration;
    return std::clamp((kHeldCouplingTo - s3) / (kHeldCouplingTo - kHeldCouplingFrom), 0.0, 1.0);
  }
  /// What the coupling kappa [1/m^2] on a patch of semi-axis a [m] takes from 1 / L3x [N/m^3] so
  /// that spin's moment in linear theory stays the same: kappa a^2 (4 / 21) / L3. The coupling's
  /// moment on spin's lateral traction tau_y = -(phi / (2 L3)) (a_y^2 - x^2) is
  /// -kappa phi a^4 b^3 32 / (315 L3) (integrated over the ellipse), the spin drive's
  /// -phi 8 a^2 b^3 / (15 L3x).
  static double spinCouplingCompensation(double kappa, double a, double L3) {
    return kappa * a * a * (4.0 / 21.0) / L3;
  }
  /// Normalised creepage e (above) at patch (a, b); infinity where muFz <= 0. `squares`, if
  /// given, receives e1^2, e2^2, e3^2 (each kind's share; finite only where muFz > 0).
  static double normalisedCreepage(double a, double b, double G, const CreepCoefficients& k,
                                   double muFz, const Creepages& c, double* squares = nullptr);

 private:
  friend class CalibrationTable;
  // Per kind (calibration::Kind) its knots and ln ratio at them (held as is: the value itself).
  std::vector<double> eps_[calibration::kKinds], logRatio_[calibration::kKinds];
  // 1 / (eps_[k][i] - eps_[k][i - 1]) at i (index 0 unused): a knot cell's weight without a
  // division.
  std::vector<double> perWidth_[calibration::kKinds];
  // Where every kind present holds kind 11's knots (the shipped table), one search of e serves
  // them all; set by CalibrationTable::at.
  bool sharedKnots_ = false;
  // The correction's cell for spin's share s3, xi's share t and e: its first corner, the strides
  // to the next xi share, spin share and branch (the eta phi < 0 one), and the weights along each.
  struct CorrectionCell {
    const double* lo;
    std::size_t alongT, alongS, branch;
    double we, wt, ws;
  };
  CorrectionCell correctionCell(double s3, double t, double e) const;
  // Whether step() takes the corrected case's lookup and exps four at a time in a vector's lanes
  // (set by CalibrationTable::at where the CPU has them; setVectorised).
  bool vectorised_ = false;
  // The knot cell [i - 1, i] holding e and e's place t in it; i = the knot count at and beyond the
  // last knot (or for NaN), where the last value is held.
  struct KnotCell {
    std::size_t i;
    double t;
  };
  // correction()'s ln multipliers into lm[first..last); false (lm untouched) where there is none.
  // `opposed`: the weight of the eta phi < 0 branch, in [0, 1].
  bool logCorrection(const double* e2, double e, double opposed, int first, int last,
                     double* lm) const;
  // The same from spin's share s3 = e3^2 / e^2 and xi's share of the rest t (in [0, 1] but for
  // rounding), for a finite e > 0 and a table with a correction (what logCorrection checks first).
  void lookUpCorrection(double s3, double t, double e, double opposed, int first, int last,
                        double* lm) const;
  static KnotCell cell(const std::vector<double>& x, const std::vector<double>& perWidth, double e);
  KnotCell cell(int kind, double e) const { return cell(eps_[kind], perWidth_[kind], e); }
  // Where a search over knots starts: the searched value's range in kBuckets equal buckets, each
  // bucket's start the knot that the search from the first knot reaches at the bucket's least
  // value (a hundredth of a bucket below it, for the rounding of v times perBucket). The search
  // goes on from there with its own test, so it ends on the knot the search from the first would:
  // one or two knots on rather than up to seventeen.
  struct SearchStart {
    static constexpr std::size_t kBuckets = 128;
    double perBucket = 0.0;
    std::vector<std::uint32_t> from;  // kBuckets; empty: no knots
    // The start for value v (the first bucket's below 0 and for NaN, the last's from the range's
    // end on).
    std::size_t at(double v) const {
      const double q = v * perBucket;
      return from[q > 0.0 ? (q < double(kBuckets) ? static_cast<std::size_t>(q) : kBuckets - 1)
                          : 0];
    }
    // Over [0, range), range > 0, of the search `search(v)` (the knot it ends on for value v).
    template <class Search>
    void set(double range, const Search& search) {
      perBucket = double(kBuckets) / range;
      from.resize(kBuckets);
      for (std::size_t b = 0; b < kBuckets; ++b)
        from[b] = static_cast<std::uint32_t>(search((double(b) - 0.01) / perBucket));
    }
  };
  // Kind 0's knot search's start (where the kinds share their knots, every kind's), and the
  // correction's over spin's share, xi's share and e; set by CalibrationTable::at.
  SearchStart knotStart_, corrS3Start_, corrTStart_, corrEpsStart_;
  // Kind 0's cell, from knotStart_ (cell(0, e), one bucket's knots searched).
  KnotCell kindCell(double e) const;
  // The three searches (each from `from`, the first knot or a bucket's start): the spin-share row
  // i (knots below s3 counted, from 0), the xi-share cell j (from 1, at most nT - 1) and the e
  // cell k (from 1, at most nE - 1; e below the last knot).
  std::size_t spinShareRow(double s3, std::size_t from) const {
    while (from < corrS3_.size() && corrS3_[from] <= s3) ++from;
    return from;
  }
  std::size_t xiShareCell(double t, std::size_t from) const {
    while (from + 1 < corrT_.size() && corrT_[from] <= t) ++from;
    return from;
  }
  std::size_t epsCell(double e, std::size_t from) const { return knotAbove(corrEps_, e, from); }
  // The first knot of x above e from `from` on (e below x's last knot).
  static std::size_t knotAbove(const std::vector<double>& x, double e, std::size_t from) {
    while (x[from] <= e) ++from;
    return from;
  }
  // Sets the four SearchStarts from the knots (CalibrationTable::at).
  void setSearchStarts();
  // The correction's grid points as step() needs them: corrLog_ at a grid point (index into
  // corrLog_ over kMultipliers) is ln of the two a/b rows' multipliers interpolated at weight
  // corrWeight_ (the upper row's), computed the first time a step's cell reaches it after
  // CalibrationTable::at picked this a/b: a model re-picking a/b every step computes the few
  // grid points its creepages reach instead of the whole grid, with the same values.
  // corrLo_, corrHi_: the rows' multipliers in the table's layout (shared with the table, so
  // that the calibration may outlive it).
  std::shared_ptr<const std::vector<double>> corrLo_, corrHi_;
  double corrWeight_ = 0.0;
  // Per grid point the pick (corrPick_) its values in corrLog_ are for; the end rows (spin shares
  // 0 and 1) hold 0 whatever the pick.
  mutable std::vector<std::uint32_t> corrFilledAt_;
  std::uint32_t corrPick_ = 1;
  // The grid point g's multipliers into corrLog_ for this pick.
  void fillGridPoint(std::size_t g) const;
  // Every grid point of cell c's corners that step() reads at the eta phi < 0 branch's weight
  // `opposed` (one branch or both), filled for this pick.
  void fillCell(const CorrectionCell& c, double opposed) const {
    constexpr std::size_t P = calibration::kMultipliers;
    const std::size_t g0 = static_cast<std::size_t>(c.lo - corrLog_.data()) / P;
    const std::size_t dT = c.alongT / P, dS = c.alongS / P, dB = c.branch / P;
    // As lookUpCorrection reads them: opposed <= 0 the first branch, >= 1 the second, else both.
    const std::size_t firstBranch = opposed >= 1.0 ? 1 : 0, endBranch = opposed <= 0.0 ? 1 : 2;
    for (std::size_t b = firstBranch; b < endBranch; ++b)
      for (std::size_t s = 0; s < 2; ++s)
        for (std::size_t t = 0; t < 2; ++t)
          for (std::size_t e = 0; e < 2; ++e) {
            const std::size_t g = g0 + b * dB + s * dS + t * dT + e;
            if (corrFilledAt_[g] != corrPick_) fillGridPoint(g);
          }
  }
  // Every grid point filled (CalibrationTable::at(a_over_b): a calibration that step() then only
  // reads).
  void fillCorrection() const;
  static double at(const std::vector<double>& r, KnotCell c) {
    return c.i == r.size() ? r.back() : r[c.i - 1] + c.t * (r[c.i] - r[c.i - 1]);
  }
  // Combined correction: spin shares (interior knots), xi shares (0 to 1), e knots, and the
  // multipliers' logarithms, the five of a grid point side by side, at index
  // ((((opposed * (nS + 2) + i) * nT + j) * nE + k) * kMultipliers + p): spin-share rows i = 0 and
  // nS + 1 are the implicit ends s3 = 0 and 1 (ln multiplier 0), row i the knot corrS3_[i - 1].
  // The reciprocal widths of the spin-share cells (nS + 1, the ends included), the xi-share cells
  // and the e cells (at a cell's upper index) spare the lookup its divisions.
  std::vector<double> corrS3_, corrT_, corrEps_;
  mutable std::vector<double> corrLog_;  // filled as step() reaches its grid points (fillCell)
  std::vector<double> corrS3PerWidth_, corrTPerWidth_, corrEpsPerWidth_;
};

/// The identified table over a/b, per FastSim mesh.
class CalibrationTable {
 public:
  /// Reads a table file: the binary format (calibration_binary.hpp; recognised by its magic) or
  /// CSV (parse). Throws std::runtime_error naming the file (and the line, in CSV) on a malformed
  /// table: a number not finite or out of its kind's range, knots not increasing or not starting
  /// at (0, 1), a/b rows whose knots differ (23x, 23s: in every a/b or in none), an unknown or
  /// repeated column, a fastsim_nx below 2 or missing in a row, a mesh in two blocks; in the binary
  /// format besides, another magic, version or schema, a size or checksum that does not match.
  static CalibrationTable load(const std::string& path);
  /// A table in CSV from a stream; `source` names it in messages.
  static CalibrationTable parse(std::istream& in, const std::string& source);
  /// A table in the binary format from its bytes, every mesh read and checked; `source` names it
  /// in messages.
  static CalibrationTable fromBinary(std::string_view bytes, const std::string& source);
  /// The table shipped with the package (config/calibration.bin, meshes 5x5 to 40x40, compiled
  /// into the library): the header is read once per process, a mesh's block only when forMesh()
  /// first needs it.
  static const CalibrationTable& shipped();
  /// Writes the table in the binary format. Throws std::runtime_error where a value is not a
  /// multiple of 1e-6 or beyond +-2147 (the format holds int32 millionths: what the identifier's
  /// CSV held, 6 decimals, read back bit for bit).
  void writeBinary(std::ostream& out) const;
  /// Writes the block of mesh nx (0: every mesh) as CSV that parse() reads back to the same
  /// values, kinds by their readable names: the table for people to read.
  void writeCsv(std::ostream& out, int nx = 0) const;
  /// The table for a FastSim mesh of nx nodes per strip, as a table of its own: an identified
  /// mesh's own; between two identified meshes of the same knots their ratios interpolated in
  /// 1/nx (the march's step along the strip; ln ratio, the coupling itself); beyond the table's
  /// meshes (or between meshes of other knots) the nearest in 1/nx, a tie to the finer, as
  /// ChiTable::forMesh. A table of one mesh (or none) is itself.
  CalibrationTable forMesh(int nx) const;
  /// nx of each mesh the table holds, increasing (one 0: a table without fastsim_nx).
  std::vector<int> meshes() const;
  /// The calibration at a/b. On a table of one mesh: narrow a table of several with forMesh()
  /// first (std::logic_error otherwise).
  PatchCalibration at(double a_over_b) const;
  /// The same into `c`, reusing the storage it holds (a model re-picking at a new a/b each step
  /// allocates nothing), the combined correction's grid points computed as c's steps first reach
  /// them (the same values as at(a_over_b)'s): c's steps write into c, so c must not be stepped
  /// from two threads at once (at(a_over_b) gives one whose steps only read).
  void at(double a_over_b, PatchCalibration* c) const;
  bool empty() const { return meshes_.empty(); }

 private:
  struct Row {
    double aOverB, logAB;
    // Per kind (calibration::Kind): knots and values (ratios, or held as is).
    std::vector<double> eps[calibration::kKinds], ratio[calibration::kKinds];
    std::vector<double> corrS3, corrT, corrEps;  // as PatchCalibration's
    // The correction's ratios, multiplier p, branch o (1: eta phi < 0), spin share q, xi share j,
    // e knot k at ((((p * 2 + o) * nS + q) * nT + j) * nE + k); shared with the calibrations
    // picked from the row (PatchCalibration::corrLo_), which read it as their steps need it.
    std::shared_ptr<const std::vector<double>> corr = std::make_shared<const std::vector<double>>();
  };
  struct Mesh {
    int nx = 0;             // 0: any
    std::vector<Row> rows;  // sorted by a/b
  };
  std::vector<Mesh> meshes_;  // sorted by nx; rows empty where binary_ reads them when asked
  // The binary form a table was read from lazily (shipped()), its meshes' blocks read once each
  // on first use; null: every mesh's rows are in meshes_.
  struct Binary;
  std::shared_ptr<const Binary> binary_;
  // Mesh m's rows (read from binary_ on first use).
  const std::vector<Row>& rowsOf(const Mesh& m) const;
  // The binary format's reader and writer (calibration_binary.cpp).
  static CalibrationTable readBinary(std::string_view bytes, const std::string& source, bool lazy);
  static std::vector<Row> readMesh(std::string_view block, std::uint32_t checksum,
                                   const std::string& source, int nx);
  // Whether two meshes' tables hold the same a/b rows and knots (identified on the same grids).
  static bool sameKnots(const std::vector<Row>& x, const std::vector<Row>& y);
};

}  // namespace wheel_rail_contact
