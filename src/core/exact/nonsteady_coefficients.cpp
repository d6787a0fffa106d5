#include "wheel_rail_contact/exact/nonsteady_coefficients.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <cmath>
#include <stdexcept>

#include "core/exact/halfspace_influence.hpp"
#include "core/exact/halfspace_normal.hpp"
#include "core/exact/halfspace_solver.hpp"

namespace wheel_rail_contact {

namespace {

struct Unknown {
  int ix, iy, comp;  // element and traction component (0 x, 1 y)
  bool mirrored;     // has a distinct mirror element at -y
};

// The scheme's matrices on the loaded elements of the y >= 0 half, for one y-parity class:
// xi drives tau_x even and tau_y odd in y; eta and phi the reverse. A: displacement at the
// element, B: at its upstream neighbour (x + dx), both including the mirror element's share.
struct FoldedSystem {
  HalfspaceGrid g;
  std::vector<Unknown> u;
  Eigen::MatrixXd A, B;
};

FoldedSystem fold(bool xiClass, const HalfspaceGrid& g, const Eigen::VectorXd& p, double nu) {
  const InfluenceKernel k(g, 1.0, nu);
  const int sign[2] = {xiClass ? 1 : -1, xiClass ? -1 : 1};
  FoldedSystem f{g, {}, {}, {}};
  for (int ix = 0; ix < g.mx; ++ix)
    for (int iy = g.my / 2; iy < g.my; ++iy) {
      if (!(p[g.index(ix, iy)] > 0.0)) continue;
      const bool mirrored = g.my - 1 - iy != iy;
      for (int c = 0; c < 2; ++c)
        if (mirrored || sign[c] > 0) f.u.push_back({ix, iy, c, mirrored});
    }
  const int n = static_cast<int>(f.u.size());
  f.A.resize(n, n);
  f.B.resize(n, n);
  auto kc = [&](int c, int d, int di, int dj) {
    return c != d ? k.xy(di, dj) : (c == 0 ? k.xx(di, dj) : k.yy(di, dj));
  };
  for (int j = 0; j < n; ++j) {
    const Unknown& s = f.u[j];
    const int jm = g.my - 1 - s.iy;
    for (int i = 0; i < n; ++i) {
      const Unknown& t = f.u[i];
      const int di = t.ix - s.ix, dj = t.iy - s.iy, djm = t.iy - jm;
      double a = kc(t.comp, s.comp, di, dj), b = kc(t.comp, s.comp, di + 1, dj);
      if (s.mirrored) {
        a += sign[s.comp] * kc(t.comp, s.comp, di, djm);
        b += sign[s.comp] * kc(t.comp, s.comp, di + 1, djm);
      }
      f.A(i, j) = a;
      f.B(i, j) = b;
    }
  }
  return f;
}

// Rigid slip per unknown for a unit creepage of `kind`.
Eigen::VectorXd shape(const FoldedSystem& f, CreepageKind kind) {
  Eigen::VectorXd v(f.u.size());
  for (size_t i = 0; i < f.u.size(); ++i) {
    const double x = f.g.xc(f.u[i].ix), y = f.g.yc(f.u[i].iy);
    if (kind == CreepageKind::kPhi)  // the spin term sits dx/6 downstream, as in the solver
      v[i] = f.u[i].comp == 0 ? -y : x + kSpinOffset * f.g.dx;
    else
      v[i] = f.u[i].comp == (kind == CreepageKind::kXi ? 0 : 1) ? 1.0 : 0.0;
  }
  return v;
}

// Force per unknown: dA (twice for a mirrored element) on the force's component.
Eigen::VectorXd weight(const FoldedSystem& f, CreepageKind kind) {
  Eigen::VectorXd v(f.u.size());
  const int comp = kind == CreepageKind::kXi ? 0 : 1;
  for (size_t i = 0; i < f.u.size(); ++i)
    v[i] = f.u[i].comp == comp ? f.g.dx * f.g.dy * (f.u[i].mirrored ? 2.0 : 1.0) : 0.0;
  return v;
}

double norm(CreepageKind kind, double a, double b) {
  return kind == CreepageKind::kPhi ? std::pow(a * b, 1.5) : a * b;  // G = 1
}

// Unit semi-axis a, G = 1: the coefficients are dimensionless.
HalfspaceGrid unitGrid(double a_over_b, int mx, int my) {
  if (!(a_over_b > 0.0) || mx < 2 || my < 1)
    throw std::invalid_argument("coefficients: need a/b > 0, mx >= 2, my >= 1");
  return HalfspaceGrid::covering(1.0, 1.0 / a_over_b, mx, my);
}

// Steady coefficient: (A - B) tau = -dx w.
double steadyOf(const Eigen::PartialPivLU<Eigen::MatrixXd>& lu, const FoldedSystem& f,
                CreepageKind kind, double b) {
  const double force = weight(f, kind).dot(lu.solve(-f.g.dx * shape(f, kind)));
  return -force / norm(kind, 1.0, b);
}

}  // namespace

NonSteadyCoefficients::NonSteadyCoefficients(CreepageKind kind, double a_over_b, double nu, int mx,
                                             int my)
    : kind_(kind) {
  const HalfspaceGrid g = unitGrid(a_over_b, mx, my);
  b_ = g.dy * my / 2.2;
  dx_ = g.dx;
  const Eigen::VectorXd p = hertzianGridPressure(g, a_, b_, 1.0, 1.0, nu);
  const FoldedSystem f = fold(kind == CreepageKind::kXi, g, p, nu);
  steady_ = steadyOf(Eigen::PartialPivLU<Eigen::MatrixXd>(f.A - f.B), f, kind, b_);
  // A - B/z = A (I - M/z), M = A^-1 B = Q H Q^T. The folded A is not symmetric (mirror terms): LU.
  const Eigen::PartialPivLU<Eigen::MatrixXd> lu(f.A);
  const Eigen::HessenbergDecomposition<Eigen::MatrixXd> hd(lu.solve(f.B));
  H_ = hd.matrixH();
  const Eigen::MatrixXd Q = hd.matrixQ();
  g_ = Q.transpose() * lu.solve(shape(f, kind));
  h_ = Q.transpose() * weight(f, kind);
}

CreepCoefficients exactSteadyCoefficients(double a_over_b, double nu, int mx, int my) {
  const HalfspaceGrid g = unitGrid(a_over_b, mx, my);
  const double b = g.dy * my / 2.2;
  const Eigen::VectorXd p = hertzianGridPressure(g, 1.0, b, 1.0, 1.0, nu);
  CreepCoefficients c;
  const FoldedSystem fx = fold(true, g, p, nu);
  c.c11 = steadyOf(Eigen::PartialPivLU<Eigen::MatrixXd>(fx.A - fx.B), fx, CreepageKind::kXi, b);
  const FoldedSystem fy = fold(false, g, p, nu);
  const Eigen::PartialPivLU<Eigen::MatrixXd> lu(fy.A - fy.B);
  c.c22 = steadyOf(lu, fy, CreepageKind::kEta, b);
  c.c23 = steadyOf(lu, fy, CreepageKind::kPhi, b);
  return c;
}

std::complex<double> NonSteadyCoefficients::solve(std::complex<double> zinv,
                                                  std::complex<double> wmean) const {
  // (I - H zinv) y = g by Gaussian elimination on the Hessenberg matrix: partial pivoting only
  // between neighbouring rows, O(n^2).
  using C = std::complex<double>;
  const int n = static_cast<int>(g_.size());
  Eigen::Matrix<C, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> k = -zinv * H_.cast<C>();
  k.diagonal().array() += 1.0;
  Eigen::VectorXcd y = g_.cast<C>();
  for (int c = 0; c + 1 < n; ++c) {
    if (std::abs(k(c + 1, c)) > std::abs(k(c, c))) {
      k.row(c).tail(n - c).swap(k.row(c + 1).tail(n - c));
      std::swap(y[c], y[c + 1]);
    }
    const C f = k(c + 1, c) / k(c, c);
    k.row(c + 1).tail(n - c) -= f * k.row(c).tail(n - c);
    y[c + 1] -= f * y[c];
  }
  for (int r = n - 1; r >= 0; --r) {
    const int m = n - r - 1;
    const C rest = m > 0 ? C((k.row(r).tail(m) * y.tail(m)).value()) : C(0.0);
    y[r] = (y[r] - rest) / k(r, r);
  }
  const C f = (-dx_ * wmean) * (h_.cast<C>().transpose() * y).value();
  return -f / norm(kind_, a_, b_);
}

std::complex<double> NonSteadyCoefficients::at(double lambda_over_a) const {
  if (!(lambda_over_a > 0.0)) throw std::invalid_argument("lambda_over_a: must be > 0");
  const double theta = 2.0 * M_PI * dx_ / (lambda_over_a * a_);  // phase advance per step
  const std::complex<double> zinv = std::polar(1.0, -theta);
  // Mean of e^{i omega t} over the step ending at t_n, relative to e^{i omega t_n}.
  const std::complex<double> wmean = (1.0 - zinv) / std::complex<double>(0.0, theta);
  return solve(zinv, wmean);
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
  const CreepCoefficients c = exactSteadyCoefficients(a_over_b, nu, mx, my);
  return kind == CreepageKind::kXi ? c.c11 : kind == CreepageKind::kEta ? c.c22 : c.c23;
}

}  // namespace wheel_rail_contact
