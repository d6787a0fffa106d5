/// The calibrated FastSim's data, declared once: the axes its values are tabulated over, the kinds
/// of value it holds, and the hand-set constants of the rule that blends them (how the values act:
/// calibration_table.hpp). The table's text form (CSV) and its binary form
/// (calibration_binary.hpp) name the kinds by KindInfo::code; identify_calibration fits them on the
/// shipped grid below.
#pragma once

#include <cmath>
#include <limits>
#include <string_view>

namespace wheel_rail_contact {
namespace calibration {

// ---- axes -----------------------------------------------------------------------------------
// A table holds one block per FastSim mesh; in each, one row per a/b (the ratios interpolated in
// ln(a/b), clamped at the ends); in each row one curve per kind over normalised creepage e (its
// knots increasing from 0, held beyond the last), and the combined correction: five multipliers
// over (sign of eta phi, spin's share s3, xi's share t, e). The shipped table's grid, which
// identify_calibration fits on by default (a table may hold another; each file states its own):

/// FastSim nodes per strip of each mesh block (fastsim_nx): a model takes its own mesh's block, or
/// the two around it interpolated in 1/nx.
inline constexpr int kMeshes[] = {5, 10, 20, 30, 40};
/// The patch's a/b of each row.
inline constexpr double kAOverB[] = {0.2, 0.5, 1, 2, 5};
/// Normalised creepage e at which every single kind is tabulated (the first 0: linear theory).
inline constexpr double kKnots[] = {0,    0.1, 0.2, 0.35, 0.5, 0.6, 0.75, 0.9, 1,
                                    1.25, 1.5, 2,   3,    4.5, 7,   10,   15};
/// The combined correction's e knots: denser where creep curves with spin turn (1.5 to 2.5), and
/// 3.75 and 5.5 in full slip, where held-out rays missed the moment by 5 % of the peak without.
inline constexpr double kCorrectionKnots[] = {0,    0.1,  0.2, 0.35, 0.5,  0.6, 0.75, 0.9,
                                              1,    1.25, 1.5, 1.65, 1.85, 2,   2.25, 3,
                                              3.75, 4.5,  5.5, 7,    10,   15};
/// Spin's share s3 = e3^2 / e^2 of the combined correction's directions, interior knots (at 0 and
/// 1 the correction is 1: the single kinds are fitted there). Each share below 0.1 and the
/// spread ones (0.625, 0.825, 0.95) were added where held-out rays between the grid's directions
/// missed by 0.02-0.055 mu fz.
inline constexpr double kSpinShares[] = {0.03, 0.045, 0.06, 0.1,   0.175, 0.25, 0.375,
                                         0.5,  0.625, 0.75, 0.825, 0.9,   0.95};
/// Xi's share of the rest t = e1^2 / (e1^2 + e2^2), from 0 to 1 (0.125, 0.375, 0.875 and 0.9375
/// added as the spin shares above).
inline constexpr double kXiShares[] = {0, 0.125, 0.25, 0.375, 0.5, 0.75, 0.875, 0.9375, 1};
/// The sign of eta phi of the correction's two branches, in their order: (xi, eta, phi) and
/// (-xi, eta, phi) are mirror images, so only sign(eta phi) matters.
inline constexpr int kSigns[] = {1, -1};

// ---- kinds ----------------------------------------------------------------------------------
/// The single kinds: one curve per a/b over e. A ratio multiplies Kalker's flexibility (stored as
/// ln ratio once read); the others are held as they are (heldAsIs).
enum Kind : int {
  kXiRatio,              ///< "11": L1's ratio, fitted on xi alone.
  kEtaRatio,             ///< "22": L2's ratio, fitted on eta alone with kEtaCoupling.
  kSpinRatio,            ///< "23": L3's ratio, fitted on spin alone with kSpinDriveRatio.
  kSpinDriveRatio,       ///< "23x": L3x (spin's longitudinal drive) over L3; knot 0 gives C33.
  kSpinBoundShape,       ///< "23s": the bound's shape under spin alone, in (0, 1].
  kEtaCoupling,          ///< "22c": lateral coupling c, eta's moment through Poisson, any sign.
  kEtaDriveSlope,        ///< "22b": slope beta of eta's drive along the strip, xi beside eta.
  kEtaRatioNoSpin,       ///< "22n": L2's ratio where spin has no share (replaces 22 there).
  kEtaCouplingNoSpin,    ///< "22cn": the coupling where spin has no share (replaces 22c there).
  kEtaBoundShapeNoSpin,  ///< "22s": eta's bound shape where spin has no share, [-1, 2].
  kKinds
};
/// The combined correction's multipliers, side by side at each grid point in this order.
enum Multiplier : int {
  kXiMultiplier,         ///< "c1": multiplies L1.
  kEtaMultiplier,        ///< "c2": multiplies L2.
  kSpinMultiplier,       ///< "c3": multiplies L3 (and L3x with it).
  kShapeMultiplier,      ///< "cs": multiplies the bound's shape.
  kSpinDriveMultiplier,  ///< "c3x": multiplies L3x besides L3's (optional: 1 where absent).
  kMultipliers
};

// Ranges (hand-set, as the blend's constants below):
/// The bound's shape is at most this (flattenedBound stays positive below 4).
inline constexpr double kMaxBoundShape = 2.0;
/// Eta's bound shape (22s) at least this (below it eta's bound peaks sharper than any fit asks).
inline constexpr double kMinEtaShape = -1.0;
/// Eta's drive's slope (22b) is clamped to +-this (its gain stays finite and positive).
inline constexpr double kMaxEtaSlope = 2.5;

/// A kind's names and the range its values must lie in (a table outside it is refused).
struct KindInfo {
  std::string_view code;  ///< the table's short name (CSV column `kind`)
  std::string_view name;  ///< the same, readable (accepted in CSV too)
  bool heldAsIs;          ///< the value itself is interpolated, else a ratio (its logarithm)
  bool oneAtZero;         ///< its value at e = 0 must be 1 (a ratio linear theory fixes)
  double min, max;        ///< a ratio's range is (0, max], a value held as is [min, max]
};
inline constexpr double kAny = std::numeric_limits<double>::infinity();
inline constexpr KindInfo kKindInfo[kKinds] = {
    {"11", "xi_ratio", false, true, 0.0, kAny},
    {"22", "eta_ratio", false, true, 0.0, kAny},
    {"23", "spin_ratio", false, true, 0.0, kAny},
    {"23x", "spin_drive_ratio", false, false, 0.0, kAny},
    {"23s", "spin_bound_shape", false, false, 0.0, 1.0},
    {"22c", "eta_coupling", true, false, -kAny, kAny},
    {"22b", "eta_drive_slope", true, false, -kMaxEtaSlope, kMaxEtaSlope},
    {"22n", "eta_ratio_no_spin", false, true, 0.0, kAny},
    {"22cn", "eta_coupling_no_spin", true, false, -kAny, kAny},
    {"22s", "eta_bound_shape_no_spin", true, false, kMinEtaShape, kMaxBoundShape}};
inline constexpr KindInfo kMultiplierInfo[kMultipliers] = {
    {"c1", "xi_multiplier", false, true, 0.0, kAny},
    {"c2", "eta_multiplier", false, true, 0.0, kAny},
    {"c3", "spin_multiplier", false, true, 0.0, kAny},
    {"cs", "shape_multiplier", false, true, 0.0, kAny},
    {"c3x", "spin_drive_multiplier", false, true, 0.0, kAny}};

// ---- the blend's hand-set constants ---------------------------------------------------------
// Chosen by hand, not identified: the data was identified with them, so a change here needs the
// table identified again (identify_calibration). Where each acts: calibration_table.hpp.

/// e from which the flexibilities are all CONTACT's L_crss (blend weight min(1, e / this)).
inline constexpr double kCrssFrom = 5.0;
/// Spin's share below which the bound's shape is moved towards Hertz's moment in full slip.
inline constexpr double kSmallSpinShare = 0.25;
/// Spin's share up to which that move grows linearly from none (min(1, s3 / this)).
inline constexpr double kHertzShapeSpinShare = 0.01;
/// e from which the shape moves towards Hertz's (the lateral coupling not held).
inline constexpr double kFullSlipFrom = 2.5;
/// The same where the lateral coupling is held (small spin shares), on a narrow or round patch.
inline constexpr double kHeldFullSlipFrom = 1.5;
/// The same on a wide patch (a/b up to kWideTo).
inline constexpr double kWideHeldFullSlipFrom = 0.75;
/// e from which the shape is Hertz's moment shape, on a narrow or round patch.
inline constexpr double kFullSlipTo = 5.0;
/// The same on a wide patch.
inline constexpr double kWideFullSlipTo = 3.5;
/// a/b up to which a patch counts as wide (the blend's span the wide one).
inline constexpr double kWideTo = 0.2;
/// a/b from which a patch counts as narrow (linear in a/b between kWideTo and this).
inline constexpr double kNarrowFrom = 0.5;
/// Spin's share at which eta's no-spin kinds (22n, 22cn, 22s) and 22b's slope have faded out.
inline constexpr double kNoSpinTo = 0.03;
/// e up to which 23x's knot 0 (linear theory's spin moment) holds for the share not spin's.
inline constexpr double kLinearSpinMomentTo = 2.0;
/// e at which it has faded out (linearly from kLinearSpinMomentTo); the held coupling too.
inline constexpr double kLinearSpinMomentEnd = 4.5;
/// Spin's share up to which the lateral coupling is held in full (heldShare 1).
inline constexpr double kHeldCouplingFrom = 0.06;
/// Spin's share from which it is not held (linear between).
inline constexpr double kHeldCouplingTo = 0.12;
/// The power of eta's share of e2^2 + e3^2 that the lateral coupling is weighted with.
inline constexpr int kCouplingSharePower = 6;

// Derived, not hand-set:
/// The shape whose full-slip spin moment is Hertz's: flattenedBound's moment of pure spin in
/// full slip, on a circle, is (8/15 + (4/105) s) mu fz a, Hertz's (3 pi / 16) mu fz a.
inline constexpr double kHertzMomentShape = (3.0 * M_PI / 16.0 - 8.0 / 15.0) * 105.0 / 4.0;
/// Eta's drive's slope's share of the lateral force in linear theory, 3 pi / 32 (its gain's).
inline constexpr double kEtaSlopeForce = 3.0 * M_PI / 32.0;

}  // namespace calibration
}  // namespace wheel_rail_contact
