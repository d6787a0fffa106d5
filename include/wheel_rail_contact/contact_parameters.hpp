/// The configuration shared by contact_cli (options --NAME) and contact_node (private params
/// ~NAME): one name, one default, one validity rule for each. Units: G Pa, lengths m, forces N.
#pragma once

#include <string>
#include <vector>

namespace wheel_rail_contact {

struct ContactParameters {
  double G = 8.2e10;   ///< shear modulus of wheel and rail [Pa]
  double nu = 0.28;    ///< Poisson ratio [-]
  double mu = 0.3;     ///< Coulomb friction coefficient [-]
  double a0 = 6.0e-3;  ///< reference semi-axis along x at fz0 [m]
  double b0 = 4.0e-3;  ///< reference semi-axis along y at fz0 [m]
  double fz0 = 8.0e4;  ///< reference normal load [N]
  int nx = 20;         ///< FastSim nodes per strip [-]
  int ny = 20;         ///< FastSim strips [-]
  /// steady | shen-li | nss | exact | auto; nss (NSS-FastSim) is the package's method.
  std::string model = "nss";
  std::string mesh = "fixed";  ///< fixed | adaptive | auto
  /// Error the "auto" model may spend, as a fraction of the peak force [-]: it sets the mesh size
  /// (nx, ny are then chosen, not read) and when steady FastSim is enough.
  double tolerance = 0.05;
  /// Largest normal load the fixed mesh must cover [N]; 0 = 1.5 * fz0.
  double fz_max = 0.0;
  /// chi table file for nss; empty = the table shipped in the library (config/chi_table.csv,
  /// compiled in).
  std::string chi_table;
  /// FastSim's steady part in steady, shen-li, nss and auto: "calibrated" (flexibilities
  /// identified against the exact solver, config/calibration.bin) or "classic" (Kalker's
  /// 1982 FastSim); empty = calibrated for nss and auto, classic for the baselines steady and
  /// shen-li (see calibratedFastSim).
  std::string fastsim;
};

/// One parameter's name, default and meaning, for --help and the node's documentation.
struct ParameterDoc {
  std::string name;
  std::string unit;
  std::string default_value;
  std::string meaning;
};
std::vector<ParameterDoc> parameterDocs();

/// Throws std::invalid_argument whose message starts with the offending parameter's name.
void validate(const ContactParameters& p);

/// Set one parameter from text (the CLI and YAML paths). Throws std::invalid_argument naming the
/// parameter on an unknown name or a value that does not parse.
void setParameter(ContactParameters* p, const std::string& name, const std::string& value);

/// fz_max resolved (0 -> 1.5 fz0).
double effectiveFzMax(const ContactParameters& p);

/// fastsim resolved: true when the model runs the calibrated FastSim (see ContactParameters).
bool calibratedFastSim(const ContactParameters& p);

/// The FastSim variant the model runs, for start-up lines: "calibrated FastSim", "classic
/// FastSim", or "no FastSim" (model exact).
const char* fastsimVariantName(const ContactParameters& p);

}  // namespace wheel_rail_contact
