#include "wheel_rail_contact/fastsim/fastsim_frequency.hpp"

#include <cmath>
#include <limits>

#include "core/fastsim/fastsim.hpp"

namespace wheel_rail_contact {

namespace {

// C^ for a given flexibility F(k) at the wave's k (F = 1 for Shen & Li); a = 1, so the time term
// is (i k / a) F = i k F.
template <typename Flexibility>
std::complex<double> responseOf(CreepageKind kind, double a_over_b, double nu, int nx, int ny,
                                const Flexibility& flexibility, double lambda_over_a) {
  using C = std::complex<double>;
  const double a = 1.0, b = a / a_over_b, G = 1.0;  // C^ is scale-free: unit a and G
  const PatchMesh mesh(nx, ny, a, b);
  const Flexibilities L = kalkerFlexibilities(a, b, G, kalkerCoefficients(a_over_b, nu));
  const bool steady = !std::isfinite(lambda_over_a);
  const double k = steady ? 0.0 : 2.0 * M_PI / lambda_over_a;
  const C timeTerm = steady ? C(0.0) : C(0.0, k / a) * flexibility(k);
  C force = 0.0;
  for (int j = 0; j < ny; ++j) {
    const double dx = mesh.stripStep(j), aj = mesh.stripHalfLength(j);
    C tau = 0.0, strip = 0.0;
    for (int i = 0; i < nx; ++i) {
      const UpstreamStep step(i, dx, aj);
      const double h = step.h, xMid = step.xMid;
      const double drive = kind == CreepageKind::kXi    ? 1.0 / L.L1
                           : kind == CreepageKind::kEta ? 1.0 / L.L2
                                                        : xMid / L.L3;
      tau = (tau / h - drive) / (1.0 / h + timeTerm);
      strip += tau;
    }
    force += strip * mesh.nodeArea(j);
  }
  const double norm = kind == CreepageKind::kPhi ? G * std::pow(a * b, 1.5) : G * a * b;
  return -force / norm;
}

}  // namespace

std::complex<double> fastsimNonSteadyCoefficient(CreepageKind kind, double a_over_b, double nu,
                                                 int nx, int ny, const ChiParameters& chi,
                                                 double lambda_over_a) {
  return responseOf(
      kind, a_over_b, nu, nx, ny, [&](double k) { return transferFunction(chi, k); },
      lambda_over_a);
}

std::complex<double> fastsimSecondOrderCoefficient(CreepageKind kind, double a_over_b, double nu,
                                                   int nx, int ny, const SecondOrderChi& chi,
                                                   double lambda_over_a) {
  return responseOf(
      kind, a_over_b, nu, nx, ny, [&](double k) { return chi.at(k); }, lambda_over_a);
}

double fastsimSteadyCoefficient(CreepageKind kind, double a_over_b, double nu, int nx, int ny) {
  return fastsimNonSteadyCoefficient(kind, a_over_b, nu, nx, ny, ChiParameters{},
                                     std::numeric_limits<double>::infinity())
      .real();
}

}  // namespace wheel_rail_contact
