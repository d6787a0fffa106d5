#include "validation/harmonic_scenes.hpp"

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace wheel_rail_contact {

namespace {

constexpr double kA = 0.02;      // semi-axes a = b [m] (the paper's combined-creepage patch)
constexpr double kV = 0.025;     // rolling speed [m/s]
constexpr double kFz = 470.5;    // normal load [N]
constexpr double kWarmUp = 8.0;  // rolling before the scored period, in a [-]
constexpr double kCreep = 1e-4;  // xi, eta amplitude [-]: F ~ 0.17 N against mu Fz ~ 189 N

double forceNorm(const ContactParameters& p, CreepageKind kind) {
  const double ab = p.a0 * p.b0;
  return kind == CreepageKind::kPhi ? p.G * std::pow(ab, 1.5) : p.G * ab;
}

}  // namespace

const char* coefficientName(CreepageKind kind) {
  return kind == CreepageKind::kXi ? "11" : kind == CreepageKind::kEta ? "22" : "23";
}

HarmonicScene harmonicScene(CreepageKind kind, double lambda_over_a, double step) {
  if (!(lambda_over_a > 0.0) || !(step > 0.0))
    throw std::invalid_argument("harmonic scene: need lambda/a > 0 and step > 0");
  HarmonicScene h;
  h.kind = kind;
  h.lambdaOverA = lambda_over_a;
  // Spin acts through the patch size: phi sqrt(ab) plays the part of xi.
  h.amplitude = kind == CreepageKind::kPhi ? kCreep / kA : kCreep;
  PaperScene& s = h.scene;
  char name[64];
  std::snprintf(name, sizeof name, "freq_%s_l%g", coefficientName(kind), lambda_over_a);
  s.name = name;
  s.params.G = 1.0e6;
  s.params.nu = 0.28;
  s.params.mu = 0.4013;
  s.params.a0 = s.params.b0 = kA;
  s.params.fz0 = s.params.fz_max = kFz;
  const double lambda = lambda_over_a * kA;
  s.period = lambda / kV;
  const int periods = 1 + static_cast<int>(std::ceil(kWarmUp / lambda_over_a));
  const int n = static_cast<int>(std::round(periods * lambda / step));
  for (int k = 0; k <= n; ++k) {
    const double q = k * step, c = h.amplitude * std::cos(2.0 * M_PI * q / lambda);
    ScenarioRow r{q / kV, kV, 0.0, 0.0, 0.0, kFz};
    (kind == CreepageKind::kXi ? r.xi : kind == CreepageKind::kEta ? r.eta : r.phi) = c;
    s.rows.push_back(r);
  }
  return h;
}

std::vector<StepOutput> harmonicResponse(const HarmonicScene& h, std::complex<double> c) {
  const double scale = -forceNorm(h.scene.params, h.kind) * h.amplitude;
  const double omega = 2.0 * M_PI / h.scene.period;
  std::vector<StepOutput> out(h.scene.rows.size());
  for (size_t k = 0; k < out.size(); ++k) {
    const double f = scale * (c * std::polar(1.0, omega * h.scene.rows[k].t)).real();
    (h.kind == CreepageKind::kXi ? out[k].fx : out[k].fy) = f;
    out[k].fz = h.scene.rows[k].fz;
  }
  return out;
}

}  // namespace wheel_rail_contact
