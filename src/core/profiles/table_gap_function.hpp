/// A contact-table node's gap function as the table holds it (GapColumns), and a lookup's
/// weighted sum of several nodes' functions, each at its own height (GapFunctionSum). Private to
/// contact_table.cpp; a header so that a test can hold the sum to the plain formula.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <vector>

#include "wheel_rail_contact/profiles/contact_search.hpp"

namespace wheel_rail_contact {

/// A node's tabulated gap function on eta = eta0 + j deta, j = 0 .. n - 1 (n >= 2): the gap, the
/// wheel circle's radius and the contact angle at the node's touching height, then their slopes
/// in the height, as six columns of n floats each in that order (so that a lookup shifts a whole
/// column to its height in one vector pass). Empty (n = 0): the search gave no gap function.
struct GapColumns {
  static constexpr int kQuantities = 3;  ///< gap, radius, angle
  double eta0 = 0.0, deta = 0.0, inv_deta = 0.0;
  int n = 0;
  std::vector<float> data;  ///< 2 kQuantities n floats

  void resize(int samples) {
    n = samples;
    data.assign(static_cast<std::size_t>(2 * kQuantities) * n, 0.0f);
  }
  float* value(int k) { return data.data() + static_cast<std::size_t>(k) * n; }
  float* perDz(int k) { return data.data() + static_cast<std::size_t>(kQuantities + k) * n; }
  const float* value(int k) const { return data.data() + static_cast<std::size_t>(k) * n; }
  const float* perDz(int k) const {
    return data.data() + static_cast<std::size_t>(kQuantities + k) * n;
  }
  bool empty() const { return n == 0; }
  double etaEnd() const { return eta0 + deta * (n - 1); }
};

/// sum_q w_q f_q(eta) over nodes' gap functions f_q, each at its own height dZ_q: f_q(eta) is
/// linear in eta between the two samples around it (clamped to the end intervals), each sample
/// at value + per_dz dZ_q. Its arithmetic is that of the plain formula, operation for operation
/// (the sums in the order the terms were added), so that rearranging the loops changes no bit:
/// each column is shifted to its height once per lookup, and the samples loop per term.
/// Reused from lookup to lookup (clear keeps the buffers).
class GapFunctionSum {
 public:
  void clear() {
    terms_.clear();
    used_ = 0;
  }
  int terms() const { return static_cast<int>(terms_.size()); }

  /// Adds w times f at height dZ (f not empty).
  void add(const GapColumns& f, double w, double dZ) {
    Term t;
    t.eta0 = f.eta0;
    t.inv_deta = f.inv_deta;
    t.last_interval = f.n - 2.0;
    t.w = w;
    t.first = used_;
    used_ += static_cast<std::size_t>(GapColumns::kQuantities) * f.n;
    if (shifted_.size() < used_) shifted_.resize(used_);
    for (int k = 0; k < GapColumns::kQuantities; ++k) {
      // value + per_dz dZ in double, a column at a time (Eigen's vector lanes).
      Eigen::Map<Eigen::ArrayXd>(shifted_.data() + t.first + static_cast<std::size_t>(k) * f.n,
                                 f.n) =
          Eigen::Map<const Eigen::ArrayXf>(f.value(k), f.n).cast<double>() +
          Eigen::Map<const Eigen::ArrayXf>(f.perDz(k), f.n).cast<double>() * dZ;
    }
    t.n = f.n;
    terms_.push_back(t);
  }

  /// offset + sum_q w_q gap_q(eta).
  double gapAt(double eta, double offset) const {
    double sum = offset;
    for (const Term& t : terms_) {
      double u;
      const int j = t.interval(eta, &u);
      const double* g = shifted_.data() + t.first;
      sum += t.w * ((1.0 - u) * g[j] + u * g[j + 1]);
    }
    return sum;
  }

  /// out[s] for s = 0 .. count - 1 at eta = eta_first + s step: eta, offset + the sum's gap, and
  /// the sum's radius and angle. Two samples at a time in Eigen's two-lane arrays (an even count
  /// is worked, a last odd one's partner discarded).
  void sample(double eta_first, double step, int count, double offset, GapSample* out) {
    const int even = count + (count & 1);
    eta_.resize(even);
    for (int k = 0; k < GapColumns::kQuantities; ++k) sums_[k].resize(even);
    for (int s = 0; s < even; ++s) {
      eta_[s] = eta_first + s * step;
      sums_[0][s] = offset;
      sums_[1][s] = 0.0;
      sums_[2][s] = 0.0;
    }
    using Pair = Eigen::Array2d;
    // Locals, so that the stores through sum are not taken to move what the loop reads.
    const double* eta = eta_.data();
    double* const sum[GapColumns::kQuantities] = {sums_[0].data(), sums_[1].data(),
                                                  sums_[2].data()};
    for (const Term& t : terms_) {
      const double* const column[GapColumns::kQuantities] = {
          shifted_.data() + t.first, shifted_.data() + t.first + t.n,
          shifted_.data() + t.first + 2 * static_cast<std::size_t>(t.n)};
      const Pair eta0 = Pair::Constant(t.eta0), inv_deta = Pair::Constant(t.inv_deta);
      const Pair w = Pair::Constant(t.w);
      const double last_interval = t.last_interval;
      for (int s = 0; s < even; s += 2) {
        // Term::interval, lane by lane.
        const Pair x = (Eigen::Map<const Pair>(eta + s) - eta0) * inv_deta;
        const Pair clamped = x.max(0.0).min(last_interval);
        const int j0 = static_cast<int>(clamped[0]), j1 = static_cast<int>(clamped[1]);
        const Pair u = x - Pair(j0, j1), v = 1.0 - u;
        for (int k = 0; k < GapColumns::kQuantities; ++k) {
          const double* c = column[k];
          Eigen::Map<Pair>(sum[k] + s) +=
              w * (v * Pair(c[j0], c[j1]) + u * Pair(c[j0 + 1], c[j1 + 1]));
        }
      }
    }
    for (int s = 0; s < count; ++s) {
      out[s].eta = eta_[s];
      out[s].gap = sums_[0][s];
      out[s].rolling_radius = sums_[1][s];
      out[s].contact_angle = sums_[2][s];
    }
  }

 private:
  struct Term {
    double eta0 = 0.0, inv_deta = 0.0;
    double last_interval = 0.0;  ///< the last row interval's first row (n - 2)
    double w = 0.0;
    std::size_t first = 0;  ///< where its shifted columns start in shifted_
    int n = 0;
    /// The interval holding eta: its first sample j = floor((eta - eta0) / deta) clamped to
    /// [0, n - 2], and u set to eta's fraction of the way from sample j to j + 1. Clamping
    /// before truncating gives floor's j (truncation is floor from 0 up) without calling floor.
    int interval(double eta, double* u) const {
      const double x = (eta - eta0) * inv_deta;
      const int j = static_cast<int>(std::min(std::max(x, 0.0), last_interval));
      *u = x - j;
      return j;
    }
  };
  std::vector<Term> terms_;
  std::vector<double> shifted_;  ///< per term its gap, radius and angle columns at its height
  std::size_t used_ = 0;         ///< of shifted_ (which only grows: no zeroing per lookup)
  std::vector<double> eta_, sums_[GapColumns::kQuantities];  ///< sample's etas and sums
};

}  // namespace wheel_rail_contact
