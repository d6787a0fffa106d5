#include "validation/varying_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace wheel_rail_contact {

namespace {

constexpr double kA0 = 0.02, kFz = 470.5, kV = 0.25, kXi = 0.003, kPhi = 0.5;

PaperScene material(const std::string& name) {
  PaperScene s;
  s.name = name;
  s.params.G = 1.0e6;
  s.params.nu = 0.28;
  s.params.mu = 0.4013;
  s.params.a0 = s.params.b0 = kA0;
  s.params.fz0 = kFz;
  // a/b = 0.7 at area pi a0^2: b = a0 / sqrt(0.7) = 1.195 a0 = b0 (1.707)^(1/3), and the patch
  // at fz_max (what the fixed meshes and the exact grid cover) must hold it.
  s.params.fz_max = 1.8 * kFz;
  return s;
}

ScenarioRow row(double q, double ab) {
  ScenarioRow r{q / kV, kV, kXi, 0.0, kPhi, kFz};
  r.a = kA0 * std::sqrt(ab);
  r.b = kA0 / std::sqrt(ab);
  return r;
}

}  // namespace

PaperScene harmonicAOverBScene(double lambda_over_a0, double step) {
  const std::string tag = std::to_string(lambda_over_a0);
  PaperScene s = material("ab_harmonic_l" + tag.substr(0, tag.find('.')));
  const double lambda = lambda_over_a0 * kA0;
  const int periods = 1 + static_cast<int>(std::ceil(8.0 * kA0 / lambda));
  s.period = lambda / kV;
  const int n = static_cast<int>(std::round(periods * lambda / step));
  for (int k = 0; k <= n; ++k) {
    const double q = k * step;
    s.rows.push_back(
        row(q, std::sqrt(0.98) * std::pow(2.0, 0.5 * std::sin(2 * M_PI * q / lambda))));
  }
  return s;
}

PaperScene stepAOverBScene(double step) {
  PaperScene s = material("ab_step");
  const double length = 8.0 * kA0;
  s.period = length / kV;
  const int n = static_cast<int>(std::round(2.0 * length / step));
  for (int k = 0; k <= n; ++k) {
    const double q = k * step;
    s.rows.push_back(row(q, q < length - 0.5 * step ? 1.4 : 0.7));
  }
  return s;
}

}  // namespace wheel_rail_contact
