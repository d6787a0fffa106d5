/// A harmonic lateral creepage on a real patch (Manchester A-2.2's right wheel): the creep-force
/// models on the patch's equivalent ellipse or on its strips (StepInput::shape) against the exact
/// transient solver on the patch's own gap and pressure (validation/patch_exact.hpp), in the time
/// domain. The frequency-response counterpart, on real patches, of harmonic_scenes.hpp.
///
/// The scene: eta = mean.eta + amplitude sin(2 pi q / lambda) (xi, phi held at the mean's),
/// rolled in steps of the exact grid's element length dq (its transient scheme needs it), lambda a
/// whole number of steps, the creepage of a step taken at its middle. The response of a force to
/// the creepage is the ratio of their discrete Fourier coefficients at the excitation's frequency
/// over the last period (so that a model that follows the creepage step by step, steady FastSim,
/// has no phase), after at least 8 a of rolling (the memory of the start, about 2 a, died out).
/// Units SI; forces on the wheel in the candidate's contact frame, mz about its contact point.
#pragma once

#include <complex>
#include <string>
#include <vector>

#include "core/fastsim/fastsim.hpp"
#include "validation/patch_exact.hpp"
#include "wheel_rail_contact/contact_model.hpp"
#include "wheel_rail_contact/fastsim/patch_shape.hpp"

namespace wheel_rail_contact {

/// One patch of A-2.2's right wheel with our normal solution and the exact one.
struct RealPatch {
  std::string name;    ///< e.g. "tread_y0.5", "corner_y5"
  NormalPatch normal;  ///< ours: fn, equivalent ellipse a, b, strips, method
  PatchShape shape;    ///< its strips, eta from the candidate's contact point
  /// The exact solution's own strips: each grid column's loaded extent (symmetric about x = 0, as
  /// the gap is) and peak pressure, so that a model on them sees the exact normal solution and
  /// its error is the tangential model's alone.
  PatchShape exact_shape;
  ExactPatch exact;     ///< the exact normal solution on the patch's gap at the wheel's load
  Creepages creepages;  ///< the case's own at the contact point
  double G = 82e9, nu = 0.28;
  /// WheelsetContact's choice: the strips for a non-Hertzian, blended or beyond-table patch.
  bool strips_by_default = false;
};

/// The patch of zone `zone` on A-2.2's right wheel at the lateral shift y_mm (a22_cases.csv at
/// `cases_csv`), the exact solution on an exact_mx x exact_my grid. Throws std::runtime_error if
/// the state or the patch is not there or not solved.
RealPatch a22RightPatch(const std::string& cases_csv, double y_mm, ContactZone zone, int exact_mx,
                        int exact_my);

struct PatchHarmonicScene {
  double lambda_over_a = 0.0;        ///< as run: lambda = period_steps dq, over the ellipse's a [-]
  double dq = 0.0;                   ///< rolled distance per step [m]
  int period_steps = 0;              ///< steps per period
  double amplitude = 0.0;            ///< eta's amplitude [-]
  std::vector<Creepages> creepages;  ///< per step
};

/// The scene at about lambda_over_a (rounded to whole steps, at least 4 a period). The amplitude
/// is `amplitude` if > 0, else a linear one: the steady lateral force about 1e-3 mu fn.
PatchHarmonicScene patchHarmonicScene(const RealPatch& patch, double lambda_over_a, double mu,
                                      double amplitude = 0.0, const Creepages& mean = {});

/// The exact transient solver through the scene (forces fx, fy = fs, mz per step; status
/// kNotConverged on a step the solver did not converge).
std::vector<StepOutput> runExactHarmonic(const RealPatch& patch, const PatchHarmonicScene& scene,
                                         double mu);

enum class PatchGeometry {
  kEllipse,      ///< the equivalent ellipse a, b with Hertz's pressure (no shape)
  kStrips,       ///< our normal solution's strips (RealPatch::shape), fn ours
  kExactStrips,  ///< the exact solution's strips (RealPatch::exact_shape), fn the exact one
};
const char* toString(PatchGeometry g);  ///< "ellipse", "strips", "exact_strips"

/// A creep-force model of `p` (its G, nu, a0, b0, fz0 set from the patch; mu, model, mesh the
/// caller's) through the scene on `geometry`, flexibilities from our equivalent ellipse; V = 1 m/s.
std::vector<StepOutput> runModelHarmonic(const RealPatch& patch, const PatchHarmonicScene& scene,
                                         ContactParameters p, PatchGeometry geometry);

/// The complex response of fx, fs, mz to eta over the last period: F^ / eta^ at the excitation's
/// frequency ([N], [N], [N m] per unit creepage); steady linear theory gives fs^ = -C22 G a b.
struct PatchResponse {
  std::complex<double> fx, fs, mz;
};
PatchResponse harmonicResponse(const PatchHarmonicScene& scene,
                               const std::vector<StepOutput>& forces);

/// The exact steady response about `mean`: the difference of the steady solutions at eta +-
/// amplitude / 2 over the amplitude (real; linear theory's gains when the mean is zero).
PatchResponse exactSteadyResponse(const RealPatch& patch, double amplitude, const Creepages& mean,
                                  double mu);

/// RMS of |(fx, fs) - reference| over the last period / peak |reference| there.
double patchHarmonicError(const PatchHarmonicScene& scene, const std::vector<StepOutput>& model,
                          const std::vector<StepOutput>& reference);

}  // namespace wheel_rail_contact
