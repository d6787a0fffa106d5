/// Model "auto": no more model than the scene needs. Steady FastSim while the inputs change slowly
/// compared with the patch's relaxation length, NSS-FastSim while they do not; both on one mesh
/// whose size comes from the error tolerance. Steady FastSim leaves its traction as the history, so
/// NSS-FastSim takes over without a jump; the way back blends the two over two patch transits.
/// On a non-Hertzian patch (StepInput::shape) it runs the patch's strips only where its equivalent
/// ellipse would err by more than its share of the tolerance (PatchShapeMonitor), the ellipse
/// otherwise.
/// Units as in contact_model.hpp; lengths m, travelled distance q m.
#pragma once

#include "core/models/nss_model.hpp"
#include "wheel_rail_contact/geometry/kalker_coefficients.hpp"

namespace wheel_rail_contact {

/// How fast the inputs change per distance rolled, as the force error steady FastSim would make:
/// a first-order lag of relaxation length l gives F_steady - F = l dF/dq, so the estimate is
/// l |dF_lin/dq| / |F_lin| (linear-theory force of the creepages, peaks over the last `window`),
/// and 0.3 l |dfz/dq| / fz for the load (weight from the chart's varying-load scenes). A step's own
/// a, b enter F_lin through Kalker's coefficients at its a/b and its area.
class SteadinessMonitor {
 public:
  /// l: relaxation length [m]; window: distance over which the peaks are held (between half of it
  /// and all of it) [m];
  /// c: Kalker's coefficients weighting xi, eta and spin into a force; sqrtAb: sqrt(a0 b0) [m];
  /// nu: Poisson's ratio, for the coefficients at a step's own a/b (StepInput::a, b).
  SteadinessMonitor(double l, double window, const CreepCoefficients& c, double sqrtAb, double nu);
  /// One usable step (dq = |V| dt > 0, fz > 0). Returns the current estimate [-].
  double update(const StepInput& in);
  void reset();
  double estimate() const { return estimate_; }

 private:
  struct Peaks {
    double slope = 0.0, size = 0.0, load = 0.0;  // |dF_lin/dq|, |F_lin|, |dfz/dq| / fz
  };
  double l_, bucket_, sqrtAb_, nu_;
  CreepCoefficients c_;
  bool primed_ = false;
  double fx_ = 0.0, fy_ = 0.0, fz_ = 0.0;  // previous linear force (per G a b) and load
  Peaks held_, current_;                   // the previous half window's and this one's
  double travelled_ = 0.0;                 // distance rolled in the current half window [m]
  double estimate_ = 0.0;
};

/// How far a non-Hertzian patch's force departs from its equivalent ellipse's, predicted without
/// running either: the strips' and the ellipse's linear-theory forces (FastSim's, with the
/// flexibilities L1, L2, L3 of the ellipse a, b that both run on), each saturated along its own
/// direction by the simplified theory's curve
///   F = mu fz g(|F_lin| / (mu fz)) F_lin / |F_lin|,   g(s) = s - s^2/3 + s^3/27 (s < 3), 1 beyond.
/// On strip j (lateral position y_j from the reference point, width w_j, half-length h_j) FastSim's
/// linear traction integrates to
///   Fx = -(xi S2 / L1 - phi S2y / L3),   Fy = -(eta S2 / L2 + phi S3 / L3),
///   S2 = sum 2 w_j h_j^2,   S2y = sum 2 w_j h_j^2 y_j,   S3 = sum (2/3) w_j h_j^3.
/// The ellipse is placed at the strips' centre y_c = S2y / S2 (its creepages there: xi - phi y_c,
/// eta, phi), where Kalker's linear theory gives Fx = -(xi - phi y_c) E2 / L1,
/// Fy = -(eta E2 / L2 + phi E3 / L3), E2 = 8 a^2 b / 3, E3 = pi a^3 b / 4. So S2 against E2 weighs
/// the strips' lengths against the ellipse's, S3 against E3 the spin's lateral drive, and the
/// spin's lever of an off-centre patch enters through y_c.
struct ShapeDeparture {
  double difference = 0.0;  ///< |F_ellipse - F_strips|, saturated [N]
  double force = 0.0;       ///< |F_strips|, saturated [N]
  double centre = 0.0;      ///< y_c, the ellipse's lateral place from the reference point [m]
};
/// For a step with a shape (in.shape, in.a, in.b given); G [Pa], nu, mu [-]. Zero without a shape.
ShapeDeparture ellipseDeparture(const StepInput& in, double G, double nu, double mu);

/// Whether the patch's strips are needed: the ellipse's predicted error, the peak of
/// ShapeDeparture::difference over the peak of its force over the last half to whole `window`
/// rolled (as SteadinessMonitor holds its peaks: a harmonic input keeps one estimate over its
/// period), the error measure of the speed-against-accuracy chart (RMS error over the peak force;
/// for a held force the error over the force, at most the error over mu fz the benchmark scores).
class PatchShapeMonitor {
 public:
  explicit PatchShapeMonitor(double window) : bucket_(0.5 * window) {}
  /// One step with a shape (dq >= 0 rolled since the previous one). Returns the estimate [-].
  double update(const ShapeDeparture& d, double dq);
  void reset();
  double estimate() const { return estimate_; }

 private:
  struct Peaks {
    double difference = 0.0, force = 0.0;
  };
  double bucket_;
  double travelled_ = 0.0;
  Peaks held_, current_;
  double estimate_ = 0.0;
};

class AutoModel : public ContactModel {
 public:
  /// p.model must be "auto"; p.nx, p.ny are replaced by meshForTolerance(p.tolerance, the
  /// variant): calibrated FastSim when `calibration` is not empty, classic otherwise.
  AutoModel(const ContactParameters& p, const ChiTable& chi,
            const CalibrationTable& calibration = CalibrationTable());
  StepOutput step(const StepInput& in) override;
  void reset() override;
  /// "auto:steady", "auto:nss" or "auto:blend": what produced the last step.
  std::string name() const override;
  std::string choices() const override;

  bool nonSteady() const { return mode_ != Mode::kSteady; }  ///< the last step ran NSS-FastSim
  int meshSize() const { return n_; }                        ///< nodes per strip and strips chosen
  bool runsCalibratedFastSim() const { return calibrated_; }
  double relaxationLength() const { return l_; }  ///< at fz0 [m]
  const SteadinessMonitor& monitor() const { return monitor_; }
  /// The last step ran on the patch's strips (StepInput::shape), not on its equivalent ellipse.
  bool onStrips() const { return strips_; }
  const PatchShapeMonitor& shapeMonitor() const { return shapeMonitor_; }

 private:
  ContactParameters p_;
  bool calibrated_;  // runs the calibrated FastSim (the mesh ladder depends on it)
  int n_;
  double l_;
  NssModel nss_;
  enum class Mode { kSteady, kNss, kHandBack };
  void choose(const StepInput& in);
  StepOutput handBack(const StepInput& in);
  // The step as the model runs it: without its shape where the ellipse suffices.
  StepInput chooseGeometry(const StepInput& in);
  // The moment of a step on the ellipse taken about the creepages' reference point.
  StepOutput aboutReference(StepOutput out) const;

  SteadinessMonitor monitor_;
  Mode mode_ = Mode::kSteady;
  double calm_ = 0.0;    // distance rolled since the estimate fell below the return threshold [m]
  double handed_ = 0.0;  // distance rolled since the hand-back began [m]
  PatchShapeMonitor shapeMonitor_;
  bool strips_ = false;
  double centre_ = 0.0;  // the ellipse's lateral place from the reference point this step [m]
};

/// The smallest n whose n x n NSS-FastSim, in the FastSim variant auto runs (classic or
/// calibrated), stays within `tolerance` (RMS error over the peak force) on the
/// speed-against-accuracy chart's scenes; 20 when none does. One ladder per variant.
int meshForTolerance(double tolerance, bool calibrated);

/// The least worst error NSS-FastSim reaches on the chart's scenes within reach, per variant: a
/// tighter tolerance is reported at start-up as out of reach.
double nssReachOnTheChart(bool calibrated);

/// The relaxation length l [m] at fz0 of NSS-FastSim with `chi`: the l of a first-order lag with
/// the same steady-state error |1 - C^(lambda)/C| at lambda/a = 50, the largest over the kinds.
double nssRelaxationLength(const ContactParameters& p, const ChiTable& chi);

}  // namespace wheel_rail_contact
