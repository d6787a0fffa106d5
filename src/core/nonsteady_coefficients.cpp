#include "wheel_rail_contact/nonsteady_coefficients.hpp"

#include <Eigen/LU>
#include <cmath>
#include <stdexcept>

#include "wheel_rail_contact/halfspace_influence.hpp"
#include "wheel_rail_contact/halfspace_normal.hpp"

namespace wheel_rail_contact {

namespace {

struct Unknown {
  int ix, iy, comp;  // element and traction component (0 x, 1 y)
  bool mirrored;     // has a distinct mirror element at -y
};

}  // namespace

NonSteadyCoefficients::NonSteadyCoefficients(CreepageKind kind, double a_over_b, double nu, int mx,
                                             int my)
    : kind_(kind) {
  if (!(a_over_b > 0.0) || mx < 2 || my < 1)
    throw std::invalid_argument("coefficients: need a/b > 0, mx >= 2, my >= 1");
  b_ = a_ / a_over_b;
  const HalfspaceGrid g = HalfspaceGrid::covering(a_, b_, mx, my);
  const InfluenceKernel k(g, 1.0, nu);
  dx_ = g.dx;
  // y-parity of the traction components: xi drives tau_x even, tau_y odd; eta and phi the reverse.
  const int sign[2] = {kind == CreepageKind::kXi ? 1 : -1, kind == CreepageKind::kXi ? -1 : 1};
  const Eigen::VectorXd p = hertzianGridPressure(g, a_, b_, 1.0, 1.0, nu);
  std::vector<Unknown> u;
  for (int ix = 0; ix < mx; ++ix)
    for (int iy = my / 2; iy < my; ++iy) {
      if (!(p[g.index(ix, iy)] > 0.0)) continue;
      const bool mirrored = my - 1 - iy != iy;
      for (int c = 0; c < 2; ++c)
        if (mirrored || sign[c] > 0) u.push_back({ix, iy, c, mirrored});
    }
  const int n = static_cast<int>(u.size());
  A_.resize(n, n);
  B_.resize(n, n);
  auto kc = [&](int c, int d, int di, int dj) {
    return c != d ? k.xy(di, dj) : (c == 0 ? k.xx(di, dj) : k.yy(di, dj));
  };
  for (int j = 0; j < n; ++j) {
    const Unknown& s = u[j];
    const int jm = my - 1 - s.iy;
    for (int i = 0; i < n; ++i) {
      const Unknown& f = u[i];
      const int di = f.ix - s.ix, dj = f.iy - s.iy, djm = f.iy - jm;
      double a = kc(f.comp, s.comp, di, dj), b = kc(f.comp, s.comp, di + 1, dj);
      if (s.mirrored) {
        a += sign[s.comp] * kc(f.comp, s.comp, di, djm);
        b += sign[s.comp] * kc(f.comp, s.comp, di + 1, djm);
      }
      A_(i, j) = a;
      B_(i, j) = b;
    }
  }
  shape_.resize(n);
  weight_.resize(n);
  const int forceComp = kind == CreepageKind::kXi ? 0 : 1;
  for (int i = 0; i < n; ++i) {
    const double x = g.xc(u[i].ix), y = g.yc(u[i].iy);
    if (kind == CreepageKind::kPhi)
      shape_[i] = u[i].comp == 0 ? -y : x;
    else
      shape_[i] = u[i].comp == forceComp ? 1.0 : 0.0;
    weight_[i] = u[i].comp == forceComp ? g.dx * g.dy * (u[i].mirrored ? 2.0 : 1.0) : 0.0;
  }
}

std::complex<double> NonSteadyCoefficients::solve(std::complex<double> zinv,
                                                  std::complex<double> wmean) const {
  const Eigen::MatrixXcd m = A_.cast<std::complex<double>>() - zinv * B_;
  const Eigen::VectorXcd rhs = (-dx_ * wmean) * shape_.cast<std::complex<double>>();
  const Eigen::VectorXcd tau = m.partialPivLu().solve(rhs);
  const std::complex<double> f = weight_.cast<std::complex<double>>().dot(tau);
  const double norm = kind_ == CreepageKind::kPhi ? std::pow(a_ * b_, 1.5) : a_ * b_;
  return -f / norm;  // G = 1
}

std::complex<double> NonSteadyCoefficients::at(double lambda_over_a) const {
  if (!(lambda_over_a > 0.0)) throw std::invalid_argument("lambda_over_a: must be > 0");
  const double theta = 2.0 * M_PI * dx_ / (lambda_over_a * a_);  // phase advance per step
  const std::complex<double> zinv = std::polar(1.0, -theta);
  // Mean of e^{i omega t} over the step ending at t_n, relative to e^{i omega t_n}.
  const std::complex<double> wmean = (1.0 - zinv) / std::complex<double>(0.0, theta);
  return solve(zinv, wmean);
}

double NonSteadyCoefficients::steady() const {
  return solve(1.0, 1.0).real();
}

std::complex<double> exactNonSteadyCoefficient(CreepageKind kind, double a_over_b,
                                               double lambda_over_a, double nu, int mx, int my) {
  return NonSteadyCoefficients(kind, a_over_b, nu, mx, my).at(lambda_over_a);
}

std::vector<std::complex<double>> exactNonSteadyCurve(CreepageKind kind, double a_over_b,
                                                      const std::vector<double>& lambda_over_a,
                                                      double nu, int mx, int my) {
  const NonSteadyCoefficients c(kind, a_over_b, nu, mx, my);
  std::vector<std::complex<double>> out;
  for (double l : lambda_over_a) out.push_back(c.at(l));
  return out;
}

double exactSteadyCoefficient(CreepageKind kind, double a_over_b, double nu, int mx, int my) {
  return NonSteadyCoefficients(kind, a_over_b, nu, mx, my).steady();
}

}  // namespace wheel_rail_contact
