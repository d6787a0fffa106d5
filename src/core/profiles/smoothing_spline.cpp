#include "core/profiles/smoothing_spline.hpp"

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace wheel_rail_contact {

SmoothingSpline2d::SmoothingSpline2d(const std::vector<double>& t,
                                     const std::vector<Eigen::Vector2d>& p,
                                     const std::vector<double>& w, double lambda) {
  const int n = static_cast<int>(t.size());
  if (n < 3 || p.size() != t.size() || w.size() != t.size())
    throw std::invalid_argument("SmoothingSpline2d: needs n >= 3 and as many points and weights");
  if (!(lambda >= 0.0) || !std::isfinite(lambda))
    throw std::invalid_argument("SmoothingSpline2d: lambda must be finite and >= 0");
  std::vector<double> h(n - 1);
  for (int i = 0; i + 1 < n; ++i) {
    h[i] = t[i + 1] - t[i];
    if (!(h[i] > 0.0)) throw std::invalid_argument("SmoothingSpline2d: t must increase strictly");
  }
  for (double wi : w)
    if (!(wi > 0.0) || !std::isfinite(wi))
      throw std::invalid_argument("SmoothingSpline2d: weights must be finite and > 0");

  // Unknowns: the second derivatives gamma at the n - 2 inner knots (natural ends: gamma = 0).
  const int m = n - 2;
  using Sparse = Eigen::SparseMatrix<double>;
  std::vector<Eigen::Triplet<double>> qt, rt;
  for (int j = 0; j < m; ++j) {  // column j belongs to knot j + 1
    const double hl = h[j], hr = h[j + 1];
    qt.emplace_back(j, j, 1.0 / hl);
    qt.emplace_back(j + 1, j, -1.0 / hl - 1.0 / hr);
    qt.emplace_back(j + 2, j, 1.0 / hr);
    rt.emplace_back(j, j, (hl + hr) / 3.0);
    if (j + 1 < m) {
      rt.emplace_back(j, j + 1, hr / 6.0);
      rt.emplace_back(j + 1, j, hr / 6.0);
    }
  }
  Sparse Q(n, m), R(m, m);
  Q.setFromTriplets(qt.begin(), qt.end());
  R.setFromTriplets(rt.begin(), rt.end());
  Eigen::VectorXd winv(n);
  for (int i = 0; i < n; ++i) winv[i] = 1.0 / w[i];
  const Sparse WinvQ = winv.asDiagonal() * Q;
  Sparse A = R + lambda * (Sparse(Q.transpose()) * WinvQ);

  Eigen::MatrixXd Y(n, 2);
  for (int i = 0; i < n; ++i) Y.row(i) = p[i].transpose();
  Eigen::MatrixXd gamma = Eigen::MatrixXd::Zero(m, 2);
  if (m > 0) {
    Eigen::SimplicialLDLT<Sparse> solver(A);
    if (solver.info() != Eigen::Success)
      throw std::invalid_argument("SmoothingSpline2d: the spline's system is singular");
    gamma = solver.solve(Eigen::MatrixXd(Q.transpose() * Y));
  }
  const Eigen::MatrixXd g = Y - lambda * (WinvQ * gamma);

  knots_ = t;
  coef_.resize(4 * (n - 1));
  auto gam = [&](int i) -> Eigen::Vector2d {
    return (i == 0 || i == n - 1) ? Eigen::Vector2d::Zero() : Eigen::Vector2d(gamma.row(i - 1));
  };
  for (int k = 0; k + 1 < n; ++k) {
    const Eigen::Vector2d g0 = g.row(k), g1 = g.row(k + 1), c0 = gam(k), c1 = gam(k + 1);
    coef_[4 * k + 0] = g0;
    coef_[4 * k + 1] = (g1 - g0) / h[k] - h[k] * (2.0 * c0 + c1) / 6.0;
    coef_[4 * k + 2] = 0.5 * c0;
    coef_[4 * k + 3] = (c1 - c0) / (6.0 * h[k]);
  }
}

int SmoothingSpline2d::interval(double t) const {
  const auto it = std::upper_bound(knots_.begin(), knots_.end(), t);
  const int k = static_cast<int>(it - knots_.begin()) - 1;
  return std::clamp(k, 0, intervals() - 1);
}

SmoothingSpline2d::Value SmoothingSpline2d::at(int k, double t) const {
  const double u = t - knots_[k];
  const Eigen::Vector2d* c = &coef_[4 * k];
  Value v;
  v.f = c[0] + u * (c[1] + u * (c[2] + u * c[3]));
  v.df = c[1] + u * (2.0 * c[2] + u * 3.0 * c[3]);
  v.d2f = 2.0 * c[2] + 6.0 * u * c[3];
  return v;
}

}  // namespace wheel_rail_contact
