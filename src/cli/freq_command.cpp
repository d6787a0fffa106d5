#include "freq_command.hpp"

#include <cmath>
#include <complex>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "wheel_rail_contact/contact_parameters.hpp"
#include "wheel_rail_contact/exact/nonsteady_coefficients.hpp"
#include "wheel_rail_contact/fastsim/chi_table.hpp"
#include "wheel_rail_contact/fastsim/fastsim_frequency.hpp"

namespace wheel_rail_contact {

namespace {

std::vector<double> parseList(const std::string& name, const std::string& text) {
  std::vector<double> v;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    char* end = nullptr;
    const double x = std::strtod(item.c_str(), &end);
    if (item.empty() || end != item.c_str() + item.size() || !(x > 0.0) || !std::isfinite(x))
      throw std::invalid_argument(name + ": expected positive numbers separated by commas, got '" +
                                  text + "'");
    v.push_back(x);
  }
  if (v.empty()) throw std::invalid_argument(name + ": empty list");
  return v;
}

struct FrequencyResponse {
  std::vector<std::complex<double>> c;  // one per lambda/a
  double steady = 0.0;
};

// The one place a model's frequency response is chosen; models without one are refused by name.
FrequencyResponse frequencyResponse(const ContactParameters& p, CreepageKind kind, double ab,
                                    const std::vector<double>& lambda_over_a) {
  if (p.model == "exact") {
    const NonSteadyCoefficients c(kind, ab, p.nu, p.nx, p.ny);
    FrequencyResponse r;
    for (double l : lambda_over_a) r.c.push_back(c.at(l));
    r.steady = c.steady();
    return r;
  }
  // FastSim models: their exact linear response in the continuous-time limit
  // (fastsim_frequency.hpp).
  SecondOrderChi chi;  // shen-li: F == 1; nss: first or second order, as the table holds
  if (p.model == "nss") {
    const ChiTable table = p.chi_table.empty() ? ChiTable::shipped() : ChiTable::load(p.chi_table);
    chi = table.forMesh(p.nx).secondOrderAt(kind, ab);
  }
  FrequencyResponse r;
  r.steady = fastsimSteadyCoefficient(kind, ab, p.nu, p.nx, p.ny);
  for (double l : lambda_over_a)
    r.c.push_back(p.model == "steady"
                      ? std::complex<double>(r.steady)
                      : fastsimSecondOrderCoefficient(kind, ab, p.nu, p.nx, p.ny, chi, l));
  return r;
}

}  // namespace

int freqCommand(const ContactParameters& p, const std::string& kindText, const std::string& abText,
                const std::string& lambdaOverA, std::ostream& out) {
  const CreepageKind kind = parseCreepageKind(kindText);
  const std::vector<double> abs = parseList("ab", abText);
  if (abs.size() != 1) throw std::invalid_argument("ab: expected one value");
  const double ab = abs[0];
  if (!(ab >= 0.05 && ab <= 20.0)) throw std::invalid_argument("ab: must be in [0.05, 20]");
  if (p.nx * p.ny > 3600) throw std::invalid_argument("nx: at most nx * ny = 3600 elements");
  const std::vector<double> lambdas = parseList("lambda-over-a", lambdaOverA);
  const FrequencyResponse r = frequencyResponse(p, kind, ab, lambdas);
  out << "lambda_over_a,c_real,c_imag,magnitude,phase_deg,c_steady,magnitude_over_steady\n";
  for (size_t k = 0; k < lambdas.size(); ++k) {
    const std::complex<double> c = r.c[k];
    char line[320];
    std::snprintf(line, sizeof line, "%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g\n", lambdas[k],
                  c.real(), c.imag(), std::abs(c), std::arg(c) * 180.0 / M_PI, r.steady,
                  std::abs(c) / r.steady);
    out << line;
  }
  return 0;
}

}  // namespace wheel_rail_contact
