/// The validation scenes of Guiral et al. (2013) as scenarios for any ContactModel, and the error
/// measure we judge models by. Units SI (the paper works in mm: its spin values are read in 1/mm,
/// as CONTACT's, i.e. phi = 0.0001 /mm = 0.1 1/m — our choice, stated in doc/validation.md).
#pragma once

#include <string>
#include <vector>

#include "wheel_rail_contact/contact_model.hpp"
#include "wheel_rail_contact/scenario.hpp"

namespace wheel_rail_contact {

struct PaperScene {
  std::string name;
  ContactParameters
      params;  ///< material, friction, reference patch (model/mesh left to the caller)
  std::vector<ScenarioRow> rows;
  double period = 0.0;  ///< duration of one period of the excitation [s]
};

/// Combined creepages, eqs. 16-18 (case 1, 2 or 3): G = 1 MPa, nu = 0.28, mu = 0.4013,
/// Fz = 470.5 N, V = 25 mm/s, a = b = 20 mm; `periods` periods, V dt = `step` [m].
PaperScene combinedCreepageScene(int which, int periods, double step);

/// Varying load, section 4.2: V = 250 mm/s, Fz = Fz0 (1 + 0.25 sin 2 pi q / lambda), Fz0 = 470.5 N,
/// a0 = b0 = 20 mm at Fz0, eta = phi = 0, constant xi.
PaperScene varyingLoadScene(double xi, double lambda_over_a0, int periods, double step);

/// Runs `rows` through `model` from a fresh state (first row dt = 0, as contact_cli does).
std::vector<StepOutput> runScene(ContactModel& model, const std::vector<ScenarioRow>& rows);

struct SceneError {
  double rmsOverPeak = 0.0;   ///< RMS |F - F_exact| over the last period / peak |F_exact| there
  double rmsOverMuFz0 = 0.0;  ///< the same RMS / (mu Fz0)
  double dFxOverMuDFz = 0.0;  ///< the model's peak-to-peak Fx / (mu peak-to-peak Fz), last period
  double dFxOverMuDFzExact = 0.0;
  /// The RMS split in two, rmsOverPeak^2 = meanOverPeak^2 + rmsAboutMeanOverPeak^2: |mean error
  /// vector| over the period / peak (a bias: on the varying-load scenes mostly FastSim's own steady
  /// error, which every FastSim model shares), and the RMS of the error about that mean / peak
  /// (what follows the load: the part the time term acts on).
  double meanOverPeak = 0.0;
  double rmsAboutMeanOverPeak = 0.0;
};

/// Error of `model` against `exact` over the rows with t > t_end - period (force vector Fx, Fy).
SceneError sceneError(const PaperScene& scene, const std::vector<StepOutput>& model,
                      const std::vector<StepOutput>& exact);

}  // namespace wheel_rail_contact
