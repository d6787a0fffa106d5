#include <gtest/gtest.h>

#include <cmath>

#include "core/calibration/calibration_table.hpp"
#include "core/fastsim/fastsim.hpp"
#include "core/models/steady_model.hpp"

using namespace wheel_rail_contact;

namespace {

struct Patch {
  double a = 6e-3, b = 4e-3, G = 8.2e10, nu = 0.28, mu = 0.3, fz = 8e4;
};

CreepForces run(const Patch& p, const Creepages& c, int nx = 20, int ny = 20) {
  const PatchMesh mesh(nx, ny, p.a, p.b);
  TractionField f;
  f.resize(mesh.size());
  parabolicBound(mesh, p.a, p.b, p.fz, p.mu, &f);
  const CreepCoefficients k = kalkerCoefficients(p.a / p.b, p.nu);
  return steadyFastSim(mesh, kalkerFlexibilities(p.a, p.b, p.G, k), c, &f);
}

}  // namespace

TEST(SteadyFastSim, SmallCreepageReproducesLinearTheory) {
  for (double ab : {0.3, 1.0, 1.5, 4.0}) {
    Patch p;
    p.b = p.a / ab;
    const CreepCoefficients k = kalkerCoefficients(ab, p.nu);
    const double Gab = p.G * p.a * p.b, Gab32 = p.G * std::pow(p.a * p.b, 1.5);
    const double xi = 1e-7, eta = 1e-7, phi = 1e-5;
    EXPECT_NEAR(run(p, {xi, 0, 0}).fx, -Gab * k.c11 * xi, 0.005 * Gab * k.c11 * xi) << ab;
    EXPECT_NEAR(run(p, {0, eta, 0}).fy, -Gab * k.c22 * eta, 0.005 * Gab * k.c22 * eta) << ab;
    EXPECT_NEAR(run(p, {0, 0, phi}).fy, -Gab32 * k.c23 * phi, 0.005 * Gab32 * k.c23 * phi) << ab;
  }
}

TEST(SteadyFastSim, LateralCouplingAddsAMomentButNoForceInLinearTheory) {
  // The coupling's longitudinal traction is odd in y (kappa y times tau_y, even in y): in
  // adhesion Fx stays 0 and Fy is bit for bit the same (tau_y does not see tau_x); the moment
  // gains -int y tau_x dA. With eta's traction growing linearly from the leading edge,
  // tau_y = -(eta / L2) (a_j - x), tau_x = kappa y (eta / L2) (a_j - x)^2 / 2 and the moment's
  // gain is -kappa (eta / L2) pi a^3 b^3 / 12 (the integral of y^2 (a_j - x)^2 / 2 over the
  // ellipse).
  const Patch p;
  const CreepCoefficients k = kalkerCoefficients(p.a / p.b, p.nu);
  Flexibilities L = kalkerFlexibilities(p.a, p.b, p.G, k);
  const double eta = 1e-7, kappa = -3e4;  // about c = -0.5 on this patch
  const PatchMesh mesh(60, 60, p.a, p.b);
  TractionField f;
  f.resize(mesh.size());
  parabolicBound(mesh, p.a, p.b, p.fz, p.mu, &f);
  const CreepForces plain = steadyFastSim(mesh, L, {0, eta, 0}, &f);
  L.lateralCoupling = kappa;
  const CreepForces coupled = steadyFastSim(mesh, L, {0, eta, 0}, &f);
  EXPECT_EQ(coupled.fy, plain.fy);
  EXPECT_LT(std::abs(coupled.fx), 1e-12 * std::abs(plain.fy));
  const double gain = -kappa * (eta / L.L2) * M_PI * std::pow(p.a, 3) * std::pow(p.b, 3) / 12.0;
  // The drive takes the upstream node's tau_y, one element behind: 2.5 % low at 60 nodes a strip.
  EXPECT_NEAR(coupled.mz - plain.mz, gain, 0.04 * std::abs(gain));
  EXPECT_GT(std::abs(gain), 0.1 * std::abs(plain.mz));  // a moment worth the name
}

TEST(SteadyFastSim, EtasDriveSlopeKeepsLinearTheorysForceAndMovesTheMoment) {
  // Eta's drive (eta / L2)(1 - beta x / a) / (1 - 3 pi beta / 32) (Flexibilities::etaSlope,
  // etaGain): in adhesion each strip's lateral force is 2 g a_j^2 (1 - (beta / 3) a_j / a), whose
  // sum over the ellipse is the uniform drive's times 1 - 3 pi beta / 32; the gain restores it.
  // The moment int x tau_y changes: the drive leans towards the trailing edge for beta > 0.
  const Patch p;
  const CreepCoefficients k = kalkerCoefficients(p.a / p.b, p.nu);
  Flexibilities L = kalkerFlexibilities(p.a, p.b, p.G, k);
  const PatchMesh mesh(60, 60, p.a, p.b);
  TractionField f;
  f.resize(mesh.size());
  parabolicBound(mesh, p.a, p.b, p.fz, p.mu, &f);
  const Creepages c{0, 1e-7, 0};
  const CreepForces plain = steadyFastSim(mesh, L, c, &f);
  for (double beta : {-1.0, 0.5, 2.0}) {
    PatchCalibration::setEtaSlope(beta, p.a, &L);
    const CreepForces sloped = steadyFastSim(mesh, L, c, &f);
    EXPECT_NEAR(sloped.fy, plain.fy, 0.01 * std::abs(plain.fy)) << beta;
    EXPECT_EQ(sloped.fx, 0.0) << beta;
    EXPECT_GT(std::abs(sloped.mz - plain.mz), 0.05 * std::abs(plain.mz)) << beta;
  }
  // None: the march's drive is Kalker's, bit for bit.
  L.etaSlope = 0.0;
  L.etaGain = 1.0;
  const CreepForces none = steadyFastSim(mesh, L, c, &f);
  EXPECT_EQ(none.fy, plain.fy);
  EXPECT_EQ(none.mz, plain.mz);
}

TEST(SteadyFastSim, PatchSmallerThanTheMeshKeepsTheLinearCoefficient) {
  // A fixed mesh sized for 1.5 fz (a, b larger by 1.5^(1/3)) holds a patch smaller than itself:
  // each strip must integrate from the patch's own leading edge, not from the mesh's, and weight
  // its end nodes by the part of the patch they stand for (StripEntry), so that the linear
  // coefficients equal those on a mesh fitted to the patch.
  const Patch p;
  const double k = std::cbrt(1.5);
  for (int n : {10, 20, 40}) {
    const PatchMesh big(n, n, k * p.a, k * p.b), fitted(n, n, p.a, p.b);
    const Flexibilities L = kalkerFlexibilities(p.a, p.b, p.G, kalkerCoefficients(p.a / p.b, p.nu));
    for (const Creepages c :
         {Creepages{1e-7, 0, 0}, Creepages{0, 1e-7, 0}, Creepages{0, 0, 1e-5}}) {
      TractionField f, g;
      f.resize(big.size());
      g.resize(fitted.size());
      parabolicBound(big, p.a, p.b, p.fz, p.mu, &f);
      parabolicBound(fitted, p.a, p.b, p.fz, p.mu, &g);
      const CreepForces onBig = steadyFastSim(big, L, c, &f),
                        onFitted = steadyFastSim(fitted, L, c, &g);
      // Measured: 0.9 % (spin 2.3 %) at 10x10, 0.1 % (0.2 %) at 20x20, 0.1 % (0.16 %) at 40x40;
      // before: 10.8 % (26.7 %) at 20x20, 0.7 % (5.3 %) at 40x40.
      const double tol = (n == 10 ? 0.03 : 0.01);
      const double size = std::hypot(onFitted.fx, onFitted.fy);
      EXPECT_NEAR(onBig.fx, onFitted.fx, tol * size) << n;
      EXPECT_NEAR(onBig.fy, onFitted.fy, tol * size) << n;
      EXPECT_EQ(onBig.adhesionFraction, 1.0) << n;
    }
  }
}

TEST(SteadyFastSim, PatchSmallerThanTheMeshKeepsItsForceInPartialSlip) {
  // Partial slip on a fixed mesh sized for 1.25 fz0 (the paper's varying-load scenes, load 0.75
  // to 1.25 fz0, xi = 0.01: a thin slip zone at the trailing edge, where the bound falls to zero).
  // Wherever the patch's edge falls between nodes, each end node must carry the bound's integral
  // over the part it stands for: saturated at the bound at the node itself, the trailing zone's
  // force swung with the load, from 3.2 % below the fitted mesh's force to 0.8 % above it; now
  // -1.5 % to +1.1 % (the patch covers 17 to 20 nodes; the fitted mesh's own error at 17 nodes
  // is +1 % against 20). Tolerance 2 %.
  Patch p;
  p.a = p.b = 0.02;
  p.G = 1e6;
  p.mu = 0.4013;
  const double fz0 = 470.5, k = std::cbrt(1.25);
  const PatchMesh big(20, 20, k * p.a, k * p.b);
  for (int q = 0; q <= 25; ++q) {
    p.fz = fz0 * (0.75 + 0.02 * q);
    const double s = std::cbrt(p.fz / fz0);
    Patch now = p;
    now.a = s * p.a;
    now.b = s * p.b;
    const PatchMesh fitted(20, 20, now.a, now.b);
    const Flexibilities L = kalkerFlexibilities(now.a, now.b, p.G, kalkerCoefficients(1.0, p.nu));
    TractionField f, g;
    f.resize(big.size());
    g.resize(fitted.size());
    parabolicBound(big, now.a, now.b, p.fz, p.mu, &f);
    parabolicBound(fitted, now.a, now.b, p.fz, p.mu, &g);
    const double onBig = steadyFastSim(big, L, {0.01, 0, 0}, &f).fx,
                 onFitted = steadyFastSim(fitted, L, {0.01, 0, 0}, &g).fx;
    EXPECT_NEAR(onBig / onFitted, 1.0, 0.02) << p.fz;
  }
}

TEST(SteadyFastSim, LargeCreepageSaturatesAtMuFz) {
  const Patch p;
  for (const Creepages c : {Creepages{0.5, 0, 0}, Creepages{0, -0.5, 0}, Creepages{0.3, 0.4, 0}}) {
    const CreepForces f = run(p, c);
    EXPECT_NEAR(std::hypot(f.fx, f.fy), p.mu * p.fz, 1e-6 * p.mu * p.fz);
    EXPECT_LT(f.adhesionFraction, 0.05);
  }
  const CreepForces f = run(p, {0.3, 0.4, 0});
  EXPECT_NEAR(f.fy / f.fx,
              0.4 / 0.3 * kalkerCoefficients(1.5, 0.28).c22 / kalkerCoefficients(1.5, 0.28).c11,
              0.05);  // force leans to the stiffer axis
}

TEST(SteadyFastSim, ForcesAreOddInCreepage) {
  const Patch p;
  const Creepages c{2e-3, -1e-3, 3.0};
  const CreepForces f = run(p, c), g = run(p, {-c.xi, -c.eta, -c.phi});
  EXPECT_NEAR(f.fx, -g.fx, 1e-9 * std::abs(f.fx));
  EXPECT_NEAR(f.fy, -g.fy, 1e-9 * std::abs(f.fy));
  EXPECT_NEAR(f.mz, -g.mz, 1e-9 * std::abs(f.mz));
  const CreepForces zero = run(p, {0, 0, 0});
  EXPECT_EQ(zero.fx, 0.0);
  EXPECT_EQ(zero.fy, 0.0);
  EXPECT_EQ(zero.adhesionFraction, 1.0);
}

TEST(SteadyFastSim, PartialSlipIsBetweenTheLimitsAndConverges) {
  const Patch p;
  const Creepages c{1e-3, 0.5e-3, 0.5};
  const CreepForces ref = run(p, c, 320, 320);
  double prevErr = 1e300;
  for (int n : {10, 20, 40, 80}) {
    const CreepForces f = run(p, c, n, n);
    const double err = std::hypot(f.fx - ref.fx, f.fy - ref.fy);
    EXPECT_LT(err, prevErr) << n;
    prevErr = err;
  }
  EXPECT_LT(prevErr, 0.005 * std::hypot(ref.fx, ref.fy));
  EXPECT_GT(ref.adhesionFraction, 0.05);
  EXPECT_LT(ref.adhesionFraction, 0.95);
}

TEST(SteadyFastSim, ConvergesToTheSimplifiedTheoryCreepCurve) {
  // Kalker (1982): pure xi on a strip of half-length a_j with bound s (a_j^2 - x^2), s = mu p_s /
  // a^2, p_s = 2 Fz / (pi a b), has the closed form F_j = -s (4/3) a_j^3 [1 - (1 - k_j)^3], k_j =
  // min(1, c / (2 a_j)), c = (xi / L1) / s. Integrated over y it is the simplified theory's creep
  // curve; FastSim must approach it as the mesh is refined.
  const Patch p;
  const double c11 = kalkerCoefficients(p.a / p.b, p.nu).c11;
  const double L1 = kalkerFlexibilities(p.a, p.b, p.G, {c11, 1, 1}).L1;
  const double s = p.mu * 2.0 * p.fz / (M_PI * p.a * p.b) / (p.a * p.a);
  for (double xi : {2e-4, 6e-4, 1.5e-3, 4e-3}) {
    const double c = xi / L1 / s;
    double exact = 0.0;
    const int n = 20000;
    for (int q = 0; q < n; ++q) {
      const double y = p.b * (-1.0 + (2.0 * q + 1.0) / n);
      const double aj = p.a * std::sqrt(1.0 - y * y / (p.b * p.b));
      const double k = std::min(1.0, c / (2.0 * aj));
      exact -= s * 4.0 / 3.0 * aj * aj * aj * (1.0 - std::pow(1.0 - k, 3)) * (2.0 * p.b / n);
    }
    EXPECT_NEAR(run(p, {xi, 0, 0}, 100, 100).fx, exact, 0.003 * p.mu * p.fz) << xi;
  }
}

TEST(SteadyModel, StatusRules) {
  ContactParameters prm;
  SteadyModel m(prm);
  StepOutput o = m.step({1e-3, 20.0, 1e-3, 0, 0, 8e4});
  EXPECT_EQ(o.status, StepStatus::kOk);
  EXPECT_LT(o.fx, 0.0);
  const StepOutput held = m.step({1e-3, 0.0, 5e-3, 0, 0, 8e4});
  EXPECT_EQ(held.status, StepStatus::kStandstill);
  EXPECT_EQ(held.fx, o.fx);
  EXPECT_EQ(m.step({1e-3, 20.0, NAN, 0, 0, 8e4}).status, StepStatus::kRejected);
  EXPECT_EQ(m.step({1e-3, 20.0, 1e-3, 0, 0, 8e4}).status, StepStatus::kOk);
  EXPECT_EQ(m.step({-1e-3, 20.0, 1e-3, 0, 0, 8e4}).status, StepStatus::kRejected);
  const StepOutput back = m.step({1e-3, -2.0, 1e-3, 0, 0, 8e4});  // rolling backwards: mirrored
  EXPECT_EQ(back.status, StepStatus::kOk);
  EXPECT_GT(back.fx, 0.0);
  o = m.step({1e-3, 20.0, 1e-3, 0, 0, -5.0});
  EXPECT_EQ(o.status, StepStatus::kNoLoad);
  EXPECT_EQ(o.fx, 0.0);
}

TEST(SteadyFastSim, EveryStripMarchesAsIfAloneWhateverItsPartner) {
  // The march runs strips j and j + 1 together (and an odd last strip alone). Under a longitudinal
  // creepage the patch is symmetric in y, so strip j and strip ny - 1 - j must carry the same
  // traction, though they sit in different places of the pairs (7 strips: 0 with 1, ..., 6
  // alone). On a mesh larger than the patch the strips' loaded ranges differ as well.
  const Patch p;
  const Flexibilities L = kalkerFlexibilities(p.a, p.b, p.G, kalkerCoefficients(p.a / p.b, p.nu));
  for (const double k : {1.0, std::cbrt(1.5)}) {
    const PatchMesh mesh(9, 7, k * p.a, k * p.b);
    TractionField f;
    f.resize(mesh.size());
    parabolicBound(mesh, p.a, p.b, p.fz, p.mu, &f);
    steadyFastSim(mesh, L, {2e-3, 0.0, 0.0}, &f);  // partial slip: both branches of a node
    const double scale = f.tx.abs().maxCoeff();
    ASSERT_GT(scale, 0.0);
    for (int j = 0; j < mesh.ny(); ++j)
      for (int i = 0; i < mesh.nx(); ++i) {
        const int a = mesh.index(i, j), b = mesh.index(i, mesh.ny() - 1 - j);
        EXPECT_NEAR(f.tx(a), f.tx(b), 1e-12 * scale) << k << " strip " << j << " node " << i;
        EXPECT_EQ(f.slip(a), f.slip(b)) << k << " strip " << j << " node " << i;
      }
  }
}

TEST(SteadyFastSim, LanesMarchAsOneStripAtATime) {
  // The march takes four strips at a time in vector lanes (strip_lanes.hpp) in centre-out order
  // (the one to three left over at the edges one strip at a time, the sums added in strip order),
  // the strips' first nodes and what a group's longer strips leave one strip at a time, and stops
  // for the nodes StripSums::node's tiny path takes. Each strip must come out as from the scalar
  // reference, on a mesh fitted to the patch and on one larger than it (strips of different
  // lengths, the outermost unloaded), strip counts that leave one to three after the groups of
  // four, classic and coupled (calibrated), with spin, eta's drive's slope, zero creepage (the tiny
  // path) and a bound next to zero (the lanes' stop). Within 1e-12 relative, not bit for bit: the
  // lanes fuse multiply-adds (tractions against the largest bound, forces against mu fz); slip
  // flags and adhesion fractions equal.
  if (!stripLanesAvailable()) GTEST_SKIP() << "this CPU has no lanes";
  const Patch p;
  Flexibilities L = kalkerFlexibilities(p.a, p.b, p.G, kalkerCoefficients(p.a / p.b, p.nu));
  int slipping = 0, stuck = 0, tiny = 0;
  for (const double coupling : {-3e4, 0.0})
    for (const double k : {1.0, std::cbrt(1.5)})
      for (const int n : {5, 10, 23})
        for (const int ny : {n, n + 2}) {
          const PatchMesh mesh(n, ny, k * p.a, k * p.b);
          L.lateralCoupling = coupling;
          for (int step = 0; step < 24; ++step) {
            TractionField fl, fs;
            const double fz = p.fz * (1.0 - 0.02 * step);
            for (TractionField* f : {&fl, &fs}) {
              f->resize(mesh.size());
              parabolicBound(mesh, p.a, p.b, fz, p.mu, f);
              if (step % 6 == 5) f->bound(mesh.index(n / 2, ny / 2)) = 1e-160;
            }
            const double w = step % 8 == 0 ? 0.0 : 1.0;
            const Creepages c{w * 1.5e-3 * std::cos(step / 3.0), w * 8e-4 * std::sin(step / 2.0),
                              w * 0.4 * std::sin(step / 5.0)};
            L.etaSlope = step % 2 == 0 ? 0.0 : 40.0;
            L.etaGain = step % 2 == 0 ? 1.0 : 1.1;
            const CreepForces x = steadyFastSim(mesh, L, c, &fl, StripLanes::kOn);
            const CreepForces y = steadyFastSim(mesh, L, c, &fs, StripLanes::kOff);
            const double muFz = p.mu * fz, bound = fl.bound.maxCoeff();
            const auto at = [&] {
              return ::testing::Message()
                     << coupling << " " << k << " " << n << " " << ny << " " << step;
            };
            ASSERT_NEAR(x.fx, y.fx, 1e-12 * muFz) << at();
            ASSERT_NEAR(x.fy, y.fy, 1e-12 * muFz) << at();
            ASSERT_NEAR(x.mz, y.mz, 1e-12 * muFz * p.a) << at();
            ASSERT_EQ(x.adhesionFraction, y.adhesionFraction) << at();
            ASSERT_LE((fl.tx - fs.tx).abs().maxCoeff(), 1e-12 * bound) << at();
            ASSERT_LE((fl.ty - fs.ty).abs().maxCoeff(), 1e-12 * bound) << at();
            ASSERT_TRUE((fl.slip == fs.slip).all()) << at();
            for (int i = 0; i < mesh.size(); ++i) {
              if (fl.bound(i) <= 0.0) continue;
              ++(fl.slip(i) ? slipping : stuck);
              tiny += fl.tx(i) == 0.0 && fl.ty(i) == 0.0;
            }
          }
        }
  // Both branches of a node and the tiny path were marched.
  EXPECT_GT(slipping, 1000);
  EXPECT_GT(stuck, 1000);
  EXPECT_GT(tiny, 100);
}
