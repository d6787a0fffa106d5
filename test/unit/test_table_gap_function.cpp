// The contact table's weighted sum of its nodes' gap functions (GapFunctionSum, what a lookup
// interpolates every sample with) against the plain formula, bit for bit: the sum rearranges the
// loops (columns shifted to their heights once, samples looped per node, the row interval found
// without floor), never the arithmetic.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "core/profiles/table_gap_function.hpp"

using namespace wheel_rail_contact;

namespace {

struct Node {
  GapColumns f;
  double w = 0.0, dZ = 0.0;
};

/// One node's gap, radius or angle (k) at eta, height dZ: linear between the samples around eta,
/// floor's interval clamped to the end ones, each sample at value + per_dz dZ.
double plain(const GapColumns& f, int k, double eta, double dZ) {
  const double t = (eta - f.eta0) * f.inv_deta;
  const int j = std::min(std::max(static_cast<int>(std::floor(t)), 0), f.n - 2);
  const double u = t - j;
  return (1.0 - u) * (f.value(k)[j] + f.perDz(k)[j] * dZ) +
         u * (f.value(k)[j + 1] + f.perDz(k)[j + 1] * dZ);
}

/// offset (k = 0) or 0 plus the nodes' weighted values, added in the nodes' order.
double plainSum(const std::vector<Node>& nodes, int k, double eta, double offset) {
  double sum = k == 0 ? offset : 0.0;
  for (const Node& n : nodes) sum += n.w * plain(n.f, k, eta, n.dZ);
  return sum;
}

/// Up to twelve nodes' functions on grids of their own, as a lookup sums them: overlapping
/// stretches, gaps of micrometres to millimetres, radii about 0.46 m, angles up to 1.2 rad.
std::vector<Node> randomNodes(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> U(0.0, 1.0);
  std::vector<Node> nodes(1 + rng() % 12);
  double sw = 0.0;
  for (Node& n : nodes) {
    const int samples = 2 + static_cast<int>(rng() % 120);
    n.f.eta0 = -0.004 - 0.006 * U(rng);
    n.f.deta = (0.004 + 0.008 * U(rng)) / (samples - 1);
    n.f.inv_deta = 1.0 / n.f.deta;
    n.f.resize(samples);
    for (int s = 0; s < samples; ++s) {
      n.f.value(0)[s] = static_cast<float>(1e-3 * U(rng) - 1e-4);
      n.f.value(1)[s] = static_cast<float>(0.46 + 0.02 * U(rng));
      n.f.value(2)[s] = static_cast<float>(1.2 * U(rng) - 0.1);
      for (int k = 0; k < GapColumns::kQuantities; ++k)
        n.f.perDz(k)[s] = static_cast<float>(2.0 * U(rng) - 1.0);
    }
    n.w = U(rng);
    n.dZ = 2e-4 * U(rng) - 1e-4;
    sw += n.w;
  }
  for (Node& n : nodes) n.w /= sw;
  return nodes;
}

}  // namespace

TEST(GapFunctionSum, EveryBitAsThePlainFormula) {
  std::mt19937_64 rng(45);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  GapFunctionSum sum;  // one, reused as a lookup reuses its thread's
  long compared = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const std::vector<Node> nodes = randomNodes(rng);
    sum.clear();
    for (const Node& n : nodes) sum.add(n.f, n.w, n.dZ);
    ASSERT_EQ(sum.terms(), static_cast<int>(nodes.size()));
    const double offset = 1e-5 * (U(rng) - 0.5);
    // Samples over and beyond every node's stretch (the end intervals extrapolate), and each
    // node's own grid points (where floor's interval changes).
    const int count = 81;
    const double first = -0.012 + 0.004 * U(rng), step = (0.024 * U(rng)) / (count - 1);
    std::vector<GapSample> out(count);
    sum.sample(first, step, count, offset, out.data());
    for (int s = 0; s < count; ++s) {
      const double eta = first + s * step;
      ASSERT_EQ(out[s].eta, eta);
      for (int k = 0; k < GapColumns::kQuantities; ++k) {
        const double got = k == 0   ? out[s].gap
                           : k == 1 ? out[s].rolling_radius
                                    : out[s].contact_angle;
        ASSERT_EQ(got, plainSum(nodes, k, eta, offset)) << "trial " << trial << " sample " << s;
      }
      ASSERT_EQ(sum.gapAt(eta, offset), plainSum(nodes, 0, eta, offset));
      ++compared;
    }
    for (const Node& n : nodes)
      for (int j = 0; j < n.f.n; ++j) {
        const double eta = n.f.eta0 + j * n.f.deta;
        ASSERT_EQ(sum.gapAt(eta, offset), plainSum(nodes, 0, eta, offset));
        ++compared;
      }
  }
  EXPECT_GT(compared, 300 * 81);
}
