/// Cubic smoothing spline of a plane curve in a given parameter (the profile's chord length), the
/// profile's interpolant (include/wheel_rail_contact/profiles/profile.hpp says which and why).
#pragma once

#include <Eigen/Core>
#include <vector>

namespace wheel_rail_contact {

/// The curve f(t) = (y(t), z(t)) minimising
///   sum_i w_i |p_i - f(t_i)|^2 + lambda * integral |f''(t)|^2 dt,
/// a natural cubic spline with a knot at every t_i (Reinsch's algorithm, as in Green & Silverman,
/// "Nonparametric Regression and Generalized Linear Models", 1994, section 2.3.3). lambda = 0
/// interpolates. Stored per interval as polynomials in (t - t_k), so that evaluation costs one
/// binary search and one Horner step.
class SmoothingSpline2d {
 public:
  SmoothingSpline2d() = default;
  /// t strictly increasing (n >= 3), p and w of the same size, every w_i > 0, lambda >= 0.
  /// Throws std::invalid_argument otherwise.
  SmoothingSpline2d(const std::vector<double>& t, const std::vector<Eigen::Vector2d>& p,
                    const std::vector<double>& w, double lambda);

  struct Value {
    Eigen::Vector2d f;    ///< position
    Eigen::Vector2d df;   ///< first derivative in t
    Eigen::Vector2d d2f;  ///< second derivative in t
  };

  /// Value at t, clamped to [tBegin(), tEnd()].
  Value operator()(double t) const { return at(interval(t), t); }
  /// Value at t on interval k (t need not lie in it: the interval's polynomial is extended).
  Value at(int k, double t) const;
  /// The interval k with knot(k) <= t < knot(k + 1), clamped to [0, intervals() - 1].
  int interval(double t) const;

  int intervals() const { return static_cast<int>(knots_.size()) - 1; }
  double knot(int k) const { return knots_[k]; }
  double tBegin() const { return knots_.front(); }
  double tEnd() const { return knots_.back(); }
  /// Coefficient c_j (j = 0..3) of interval k: f = c0 + c1 u + c2 u^2 + c3 u^3, u = t - knot(k).
  const Eigen::Vector2d& coefficient(int k, int j) const { return coef_[4 * k + j]; }

 private:
  std::vector<double> knots_;
  std::vector<Eigen::Vector2d> coef_;
};

}  // namespace wheel_rail_contact
