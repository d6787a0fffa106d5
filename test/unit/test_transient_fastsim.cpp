#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/fastsim/transient_fastsim.hpp"
#include "core/models/rolling_direction.hpp"
#include "wheel_rail_contact/fastsim/second_order_flexibility.hpp"
#include "wheel_rail_contact/geometry/kalker_coefficients.hpp"

using namespace wheel_rail_contact;

namespace {
TransientState linearField(const PatchMesh& m) {  // tau_x = x, tau_y = 2 y (in metres)
  TransientState s;
  s.resize(m.size());
  for (int j = 0; j < m.ny(); ++j)
    for (int i = 0; i < m.nx(); ++i) {
      s.tx()(m.index(i, j)) = m.nodeX(i, j);
      s.ty()(m.index(i, j)) = 2.0 * m.stripY(j);
      s.sx()(m.index(i, j)) = 1.0;
    }
  return s;
}
}  // namespace

TEST(RemapState, SamePatchIsTheIdentity) {
  const PatchMesh m(12, 10, 6e-3, 4e-3);
  const TransientState in = linearField(m);
  TransientState out;
  remapState(m, in, m, &out);
  EXPECT_LT((out.tx() - in.tx()).abs().maxCoeff(), 1e-15);
  EXPECT_LT((out.ty() - in.ty()).abs().maxCoeff(), 1e-15);
  EXPECT_LT((out.sx() - in.sx()).abs().maxCoeff(), 1e-12);
}

TEST(RemapState, ShrinkingPatchInterpolatesAtFixedCoordinates) {
  const PatchMesh big(40, 40, 6e-3, 4e-3);
  PatchMesh small = big;
  small.scale(0.9 * 6e-3, 0.9 * 4e-3);
  TransientState out;
  remapState(big, linearField(big), small, &out);
  // Inside the old patch's node hull a linear field is reproduced along strips; across strips the
  // interpolation is linear too, so interior nodes carry the field at their own coordinates.
  for (int j = 4; j < 36; ++j)
    for (int i = 4; i < 36; ++i) {
      EXPECT_NEAR(out.tx()(small.index(i, j)), small.nodeX(i, j), 2e-5) << i << "," << j;
      EXPECT_NEAR(out.ty()(small.index(i, j)), 2.0 * small.stripY(j), 1e-12) << i << "," << j;
    }
}

TEST(RemapState, GrowingPatchGivesZeroOutsideTheOldOne) {
  const PatchMesh m(10, 10, 6e-3, 4e-3);
  PatchMesh grown = m;
  grown.scale(2 * 6e-3, 2 * 4e-3);
  TransientState in;
  in.resize(m.size());
  in.tx().setConstant(5.0);
  TransientState out;
  remapState(m, in, grown, &out);
  EXPECT_EQ(out.tx()(grown.index(0, 5)), 0.0);  // leading node of the grown patch lies outside
  EXPECT_EQ(out.tx()(grown.index(5, 0)), 0.0);  // outer strip lies outside
  EXPECT_NEAR(out.tx()(grown.index(5, 5)), 5.0, 1e-12);
  EXPECT_LE(out.tx().maxCoeff(), 5.0 + 1e-12);
}

TEST(AlongStripMap, SameSizeIsTheIdentity) {
  const PatchMesh m(12, 10, 6e-3, 4e-3);
  const TransientState in = linearField(m);
  AlongStripMap map(m.nx());
  map.set(1.0);
  TransientState out;
  out.resize(m.size());
  remapAlongStrips(map, in, m.ny(), &out);
  EXPECT_LT((out.tx() - in.tx()).abs().maxCoeff(), 1e-15);
  EXPECT_LT((out.ty() - in.ty()).abs().maxCoeff(), 1e-15);
  EXPECT_LT((out.sx() - in.sx()).abs().maxCoeff(), 1e-15);
}

TEST(AlongStripMap, CarriesAlongStripsAtFixedXAndKeepsEachStrip) {
  const PatchMesh big(40, 40, 6e-3, 4e-3);
  PatchMesh small = big;
  small.scale(0.9 * 6e-3, 0.9 * 4e-3);
  AlongStripMap map(big.nx());
  map.set(0.9);
  TransientState out;
  out.resize(small.size());
  remapAlongStrips(map, linearField(big), big.ny(), &out);
  for (int j = 0; j < 40; ++j)
    for (int i = 4; i < 36; ++i) {
      // Along the strip: the linear field at the new node's own x.
      EXPECT_NEAR(out.tx()(small.index(i, j)), small.nodeX(i, j), 1e-15) << i << "," << j;
      // Across strips: strip j keeps strip j's history (its old y).
      EXPECT_NEAR(out.ty()(small.index(i, j)), 2.0 * big.stripY(j), 1e-15) << i << "," << j;
    }
}

TEST(AlongStripMap, GrowingPatchGivesZeroBeyondTheOldStripEnds) {
  const PatchMesh m(10, 10, 6e-3, 4e-3);
  TransientState in;
  in.resize(m.size());
  in.tx().setConstant(5.0);
  AlongStripMap map(m.nx());
  map.set(2.0);
  TransientState out;
  out.resize(m.size());
  remapAlongStrips(map, in, m.ny(), &out);
  for (int j = 0; j < m.ny(); ++j) {
    EXPECT_EQ(out.tx()(m.index(0, j)), 0.0);  // the leading node of the grown strip lies outside
    EXPECT_EQ(out.tx()(m.index(9, j)), 0.0);  // and so does the trailing one
    EXPECT_NEAR(out.tx()(m.index(5, j)), 5.0, 1e-12);
  }
  EXPECT_LE(out.tx().maxCoeff(), 5.0 + 1e-12);
  EXPECT_GE(out.tx().minCoeff(), 0.0);
}

TEST(AlongStripMap, FusedStepEqualsCarryThenStep) {
  // Second order: zy carries the fitted spin F, and the history a second state. Within 1e-12
  // relative, not bit for bit, where the march runs in vector lanes (strip_lanes.hpp): they fuse
  // the carry's multiply-adds, remapAlongStrips does not (forces against mu fz, the history
  // against each row's largest); bit for bit one strip at a time.
  for (const bool second : {false, true}) {
    PatchMesh old(14, 12, 6e-3, 4e-3), now = old;
    now.scale(1.03 * 6e-3, 1.03 * 4e-3);
    TransientState previous = linearField(old);
    previous.tx() *= 1e6;
    previous.sy().setConstant(-3e5);
    if (second) previous.s2y().setConstant(2e5);
    AlongStripMap map(old.nx());
    map.set(now.a() / old.a());
    const Flexibilities L = kalkerFlexibilities(now.a(), now.b(), 8.2e10, {4.1, 3.6, 1.4});
    const Creepages c{1e-3, -5e-4, 0.7};
    const FilterZ zx = discretise(ChiParameters{0.4, 1.1, 0.6}, now.a(), 20.0, 5e-5);
    const FilterZ zy =
        second ? discretise(SecondOrderChi{0.744200, 1.776235, 0.511910, 0.107313, 0.021463},
                            now.a(), 20.0, 5e-5)
               : discretise(ChiParameters{0.5, 1.0, 0.7}, now.a(), 20.0, 5e-5);
    ASSERT_EQ(zy.secondOrder(), second);
    TractionField fused, separate;
    fused.resize(now.size());
    parabolicBound(now, now.a(), now.b(), 8e4, 0.3, &fused);
    separate = fused;
    TransientState a, b;
    a.resize(now.size());
    b.resize(now.size());
    const CreepForces fa =
        transientFastSim(now, L, c, 20.0, 5e-5, zx, zy, 0.97, map, previous, &a, &fused);
    remapAlongStrips(map, previous, old.ny(), &b);
    const CreepForces fb = transientFastSim(now, L, c, 20.0, 5e-5, zx, zy, 0.97, &b, &separate);
    const double muFz = 0.3 * 8e4;
    EXPECT_NEAR(fa.fx, fb.fx, 1e-12 * muFz);
    EXPECT_NEAR(fa.fy, fb.fy, 1e-12 * muFz);
    EXPECT_NEAR(fa.mz, fb.mz, 1e-12 * muFz * now.a());
    const auto near = [](const auto& u, const auto& v) {
      return (u - v).abs().maxCoeff() <= 1e-12 * v.abs().maxCoeff();
    };
    EXPECT_TRUE(near(a.tx(), b.tx()) && near(a.sy(), b.sy()));
    EXPECT_TRUE(near(a.s2y(), b.s2y()) && near(a.s2x(), b.s2x()));
    // One strip at a time, bit for bit.
    a.setStripLanes(TransientState::StripLanes::kOff);
    b.setStripLanes(TransientState::StripLanes::kOff);
    const CreepForces ga =
        transientFastSim(now, L, c, 20.0, 5e-5, zx, zy, 0.97, map, previous, &a, &fused);
    remapAlongStrips(map, previous, old.ny(), &b);
    const CreepForces gb = transientFastSim(now, L, c, 20.0, 5e-5, zx, zy, 0.97, &b, &separate);
    EXPECT_EQ(ga.fx, gb.fx);
    EXPECT_EQ(ga.fy, gb.fy);
    EXPECT_EQ(ga.mz, gb.mz);
    EXPECT_TRUE((a.tx() == b.tx()).all() && (a.sy() == b.sy()).all());
    EXPECT_TRUE((a.s2y() == b.s2y()).all() && (a.s2x() == b.s2x()).all());
    // The carried s2 reaches s: a second-order step with and without it differs.
    if (second) {
      TransientState c2 = b;
      remapAlongStrips(map, previous, old.ny(), &c2);
      c2.s2y().setZero();
      transientFastSim(now, L, c, 20.0, 5e-5, zx, zy, 0.97, &c2, &separate);
      EXPECT_GT((c2.sy() - b.sy()).abs().maxCoeff(), 1e4);
    } else {
      EXPECT_TRUE((a.s2y() == 0.0).all());
    }
  }
}

TEST(TransientFastSim, EveryStripMarchesAsIfAloneWhateverItsPartner) {
  // As for steady FastSim (test_fastsim.cpp): strips j and ny - 1 - j sit in different places of
  // the march's strip pairs, yet under a longitudinal creepage on a patch symmetric in y they must
  // keep the same traction and filter state, step after step, in place and carried, with a first-
  // and a second-order filter, on a mesh fitted to the patch and on one larger than it.
  const double a = 6e-3, b = 4e-3, fz = 8e4;
  const Flexibilities L = kalkerFlexibilities(a, b, 8.2e10, kalkerCoefficients(a / b, 0.28));
  for (const bool second : {false, true})
    for (const double k : {1.0, std::cbrt(1.5)}) {
      const PatchMesh mesh(9, 7, k * a, k * b);
      const FilterZ z =
          second ? discretise(SecondOrderChi{0.744200, 1.776235, 0.511910, 0.107313, 0.021463}, a,
                              20.0, 5e-5)
                 : discretise(ChiParameters{0.4, 1.1, 0.6}, a, 20.0, 5e-5);
      TractionField f;
      f.resize(mesh.size());
      parabolicBound(mesh, a, b, fz, 0.3, &f);
      TransientState state, previous;
      state.resize(mesh.size());
      AlongStripMap map(mesh.nx());
      map.set(1.0);
      for (int step = 0; step < 30; ++step) {
        const Creepages c{2e-3 * (1.0 + std::sin(0.3 * step)), 0.0, 0.0};
        if (step % 3 == 2) {  // a carried step (the adaptive mesh's path), the patch unchanged
          previous = state;
          transientFastSim(mesh, L, c, 20.0, 5e-5, z, z, 1.0, map, previous, &state, &f);
        } else {
          transientFastSim(mesh, L, c, 20.0, 5e-5, z, z, 1.0, &state, &f);
        }
      }
      const double scale = state.tx().abs().maxCoeff(), rate = state.sx().abs().maxCoeff();
      ASSERT_GT(scale, 0.0);
      ASSERT_GT(rate, 0.0);
      for (int j = 0; j < mesh.ny(); ++j)
        for (int i = 0; i < mesh.nx(); ++i) {
          const int p = mesh.index(i, j), q = mesh.index(i, mesh.ny() - 1 - j);
          EXPECT_NEAR(state.tx()(p), state.tx()(q), 1e-12 * scale) << second << k << j << i;
          EXPECT_NEAR(state.sx()(p), state.sx()(q), 1e-12 * rate) << second << k << j << i;
          EXPECT_EQ(f.slip(p), f.slip(q)) << second << k << j << i;
        }
    }
}

TEST(TransientFastSim, OutsideStatesHeldDecayedEqualTheFullUpdate) {
  // On a fixed mesh larger than the patch, the first-order march holds the filter states of the
  // nodes outside the patch as s / D and updates only the nodes crossing its edge
  // (TransientState). The reference takes every outside node in full: marchSecond with
  // first-order filters runs the same arithmetic with s2 = 0. Under a load that moves the patch's
  // edge across nodes every few steps, with a mirror, a rate rescale and a materialize() on the
  // way, both must give the same forces and states, within rounding (1e-12 of the force, 1e-9 of
  // the state).
  const double a0 = 6e-3, b0 = 4e-3, fz0 = 8e4, V = 20.0, dt = 5e-5;
  const PatchMesh mesh(16, 12, std::cbrt(1.5) * a0, std::cbrt(1.5) * b0);
  const Flexibilities L = kalkerFlexibilities(a0, b0, 8.2e10, kalkerCoefficients(a0 / b0, 0.28));
  const FilterZ zx = discretise(ChiParameters{0.4, 1.1, 0.6}, a0, V, dt);
  const FilterZ zy = discretise(ChiParameters{0.5, 1.0, 0.7}, a0, V, dt);
  TransientState lazy, full;
  lazy.resize(mesh.size());
  full.resize(mesh.size());
  TractionField fl, ff;
  fl.resize(mesh.size());
  ff.resize(mesh.size());
  double worstForce = 0.0;
  int crossings = 0, lastEntry = -1;
  for (int k = 0; k < 600; ++k) {
    const double fz = fz0 * (1.0 + 0.45 * std::sin(2.0 * M_PI * k / 97.0));
    const double s = std::cbrt(fz / fz0);
    parabolicBound(mesh, s * a0, s * b0, fz, 0.3, &fl);
    parabolicBound(mesh, s * a0, s * b0, fz, 0.3, &ff);
    crossings += fl.entry[mesh.ny() / 2].first != lastEntry;
    lastEntry = fl.entry[mesh.ny() / 2].first;
    const Creepages c{1e-3 * std::cos(k / 13.0), 6e-4 * std::sin(k / 7.0), 0.0};
    const double r = k % 50 == 0 ? 0.98 : 1.0;  // a history scale other than 1 now and then
    const CreepForces x = transientFastSim(mesh, L, c, V, dt, zx, zy, r, &lazy, &fl);
    const CreepForces y = transientFastSim(mesh, L, c, V, dt, zx, zy, r, &full, &ff, true);
    const double size = std::hypot(y.fx, y.fy) + 1.0;
    worstForce = std::max({worstForce, std::abs(x.fx - y.fx) / size, std::abs(x.fy - y.fy) / size,
                           std::abs(x.mz - y.mz) / (size * a0)});
    if (k == 200) {  // a reversal mirrors both (through the named rows: lazy materializes first)
      mirrorAlongX(mesh, &lazy);
      mirrorAlongX(mesh, &full);
    }
    if (k == 300) {  // a new speed rescales the rates, held or not
      lazy.scaleStates(1.3, false);
      full.scaleStates(1.3, false);
    }
    if (k == 400) lazy.materialize();
  }
  EXPECT_GT(crossings, 20);  // the patch's edge did cross nodes
  EXPECT_LT(worstForce, 1e-12);
  const double scale = full.sx().abs().maxCoeff() + full.sy().abs().maxCoeff();
  EXPECT_GT(scale, 0.0);
  EXPECT_LT((lazy.sx() - full.sx()).abs().maxCoeff(), 1e-9 * scale);
  EXPECT_LT((lazy.sy() - full.sy()).abs().maxCoeff(), 1e-9 * scale);
  EXPECT_LT((lazy.tx() - full.tx()).abs().maxCoeff(), 1e-9 * (full.tx().abs().maxCoeff() + 1.0));
}

TEST(TransientFastSim, LanesMarchAsOneStripAtATime) {
  // The march takes four strips at a time in vector lanes (strip_lanes.hpp: groups of four in
  // centre-out order, a lane repeating another once its strip ends, the one or two strips left
  // over one at a time) and stops for the nodes its guards send one strip at a time. Each strip
  // must come out as from the scalar reference (one strip at a time), on a fixed mesh larger than
  // a patch whose load varies (strips of different lengths, edges moving), on carried steps (the
  // adaptive mesh's path), first- and second-order filters, x and y on different filters, both
  // saturations, with spin, with the lateral coupling and without, with a history scale, through
  // zero creepage (the tiny path) and a bound next to zero (the lanes' stop). Within 1e-12
  // relative, not bit for bit: the lanes fuse multiply-adds (tractions against the largest bound,
  // forces against mu fz, filter states against their largest); slip flags and adhesion fractions
  // equal.
  if (!stripLanesAvailable()) GTEST_SKIP() << "this CPU has no lanes: only the scalar reference";
  const double a0 = 6e-3, b0 = 4e-3, fz0 = 8e4, V = 20.0, dt = 5e-5;
  const Flexibilities L0 = kalkerFlexibilities(a0, b0, 8.2e10, kalkerCoefficients(a0 / b0, 0.28));
  using Saturation = TransientState::Saturation;
  for (const Saturation saturation : {Saturation::kResidualAlongTraction, Saturation::kAlongGuess})
    for (const bool second : {false, true})
      for (const int n : {5, 11, 23}) {
        const PatchMesh mesh(n, n + 2, std::cbrt(1.5) * a0, std::cbrt(1.5) * b0);
        const FilterZ zx =
            second ? discretise(SecondOrderChi{0.744200, 1.776235, 0.511910, 0.107313, 0.021463},
                                a0, V, dt)
                   : discretise(ChiParameters{0.4, 1.1, 0.6}, a0, V, dt);
        const FilterZ zy = discretise(ChiParameters{0.5, 1.0, 0.7}, a0, V, dt);
        TransientState lanes, scalar, previous;
        for (TransientState* s : {&lanes, &scalar}) {
          s->resize(mesh.size());
          s->setSaturation(saturation);
        }
        lanes.setStripLanes(TransientState::StripLanes::kOn);
        scalar.setStripLanes(TransientState::StripLanes::kOff);
        TractionField fl, fs;
        fl.resize(mesh.size());
        fs.resize(mesh.size());
        AlongStripMap map(mesh.nx());
        int slipping = 0, stuck = 0;
        for (int k = 0; k < 120; ++k) {
          const double fz = fz0 * (1.0 + 0.45 * std::sin(2.0 * M_PI * k / 37.0));
          const double s = std::cbrt(fz / fz0);
          for (TractionField* f : {&fl, &fs}) {
            parabolicBound(mesh, s * a0, s * b0, fz, 0.3, f);
            // A bound next to zero: under zero creepage from rest (k = 1) the lanes stop there.
            if (k == 1 || k == 61) f->bound(mesh.index(n / 2, n / 2)) = 1e-160;
          }
          const double w = k % 40 < 4 ? 0.0 : 1.0;  // zero creepage now and then
          const Creepages c{w * 1.5e-3 * std::cos(k / 9.0), w * 8e-4 * std::sin(k / 5.0),
                            w * 0.4 * std::sin(k / 7.0)};
          const double r = k % 25 == 0 ? 0.97 : 1.0;
          // The lateral coupling (calibrated FastSim's) on every other step.
          Flexibilities L = L0;
          L.lateralCoupling = k % 2 == 0 ? -3e4 : 0.0;
          CreepForces x, y;
          if (k % 3 == 2) {  // carried, the patch stretched along the strips
            map.set(k % 2 == 0 ? 0.95 : 1.04);
            previous = lanes;
            x = transientFastSim(mesh, L, c, V, dt, zx, zy, r, map, previous, &lanes, &fl);
            previous = scalar;
            y = transientFastSim(mesh, L, c, V, dt, zx, zy, r, map, previous, &scalar, &fs);
          } else {
            x = transientFastSim(mesh, L, c, V, dt, zx, zy, r, &lanes, &fl);
            y = transientFastSim(mesh, L, c, V, dt, zx, zy, r, &scalar, &fs);
          }
          const auto at = [&] {
            return ::testing::Message()
                   << static_cast<int>(saturation) << " " << second << " " << n << " " << k;
          };
          const double muFz = 0.3 * fz, bound = fl.bound.maxCoeff();
          ASSERT_NEAR(x.fx, y.fx, 1e-12 * muFz) << at();
          ASSERT_NEAR(x.fy, y.fy, 1e-12 * muFz) << at();
          ASSERT_NEAR(x.mz, y.mz, 1e-12 * muFz * a0) << at();
          ASSERT_EQ(x.adhesionFraction, y.adhesionFraction) << at();
          ASSERT_LE((fl.tx - fs.tx).abs().maxCoeff(), 1e-12 * bound) << at();
          ASSERT_LE((fl.ty - fs.ty).abs().maxCoeff(), 1e-12 * bound) << at();
          ASSERT_TRUE((fl.slip == fs.slip).all()) << at();
          // The history: tractions against the bound, each filter state against its largest.
          const auto near = [](const auto& u, const auto& v, double scale) {
            return (u - v).abs().maxCoeff() <= 1e-12 * scale;
          };
          ASSERT_TRUE(near(lanes.tx(), scalar.tx(), bound) && near(lanes.ty(), scalar.ty(), bound))
              << at();
          ASSERT_TRUE(near(lanes.sx(), scalar.sx(), scalar.sx().abs().maxCoeff()) &&
                      near(lanes.sy(), scalar.sy(), scalar.sy().abs().maxCoeff()) &&
                      near(lanes.s2x(), scalar.s2x(), scalar.s2x().abs().maxCoeff()) &&
                      near(lanes.s2y(), scalar.s2y(), scalar.s2y().abs().maxCoeff()))
              << at();
          for (int i = 0; i < mesh.size(); ++i)
            if (fl.bound(i) > 0.0) (fl.slip(i) ? slipping : stuck) += 1;
        }
        // Both regimes were marched.
        EXPECT_GT(slipping, 100) << second << n;
        EXPECT_GT(stuck, 100) << second << n;
      }
}

TEST(TransientFastSim, CoupledMarchSettlesOnCoupledSteadyFastSim) {
  // The lateral coupling in the residual-along-traction march (calibrated nss): under constant
  // input, x and y on different filters, in partial slip, the traction settles on steady
  // FastSim's with the same coupling, whatever the step length, two strips or four at a time.
  const double a = 6e-3, b = 4e-3, fz = 8e4, V = 20.0, mu = 0.3;
  Flexibilities L = kalkerFlexibilities(a, b, 8.2e10, kalkerCoefficients(a / b, 0.28));
  L.lateralCoupling = -3e4;
  const PatchMesh mesh(24, 20, a, b);
  TractionField steady, f;
  steady.resize(mesh.size());
  f.resize(mesh.size());
  parabolicBound(mesh, a, b, fz, mu, &steady);
  parabolicBound(mesh, a, b, fz, mu, &f);
  const Creepages c{5e-4, 1.5e-3, 1.0};
  const CreepForces ref = steadyFastSim(mesh, L, c, &steady);
  Flexibilities plain = L;
  plain.lateralCoupling = 0.0;
  TractionField g;
  g.resize(mesh.size());
  parabolicBound(mesh, a, b, fz, mu, &g);
  const CreepForces uncoupled = steadyFastSim(mesh, plain, c, &g);
  ASSERT_GT(std::abs(ref.mz - uncoupled.mz), 0.02 * std::abs(ref.mz));  // the coupling acts
  int slipping = 0;
  for (int k = 0; k < mesh.size(); ++k) slipping += steady.bound(k) > 0.0 && steady.slip(k);
  ASSERT_GT(slipping, mesh.size() / 10);
  const double element = 2.0 * a / mesh.nx(), muFz = mu * fz;
  for (const auto lanes : {TransientState::StripLanes::kOff, TransientState::StripLanes::kOn})
    for (double steps : {0.3, 1.0, 4.0}) {
      const double dt = steps * element / V;
      const FilterZ zx = discretise(ChiParameters{0.4, 1.1, 0.6}, a, V, dt),
                    zy = discretise(ChiParameters{0.5, 1.0, 0.7}, a, V, dt);
      TransientState st;
      st.resize(mesh.size());
      st.setSaturation(TransientState::Saturation::kResidualAlongTraction);
      st.setStripLanes(lanes);
      CreepForces o;
      for (int k = 0; k < static_cast<int>(80.0 * a / (steps * element)); ++k)
        o = transientFastSim(mesh, L, c, V, dt, zx, zy, 1.0, &st, &f);
      EXPECT_NEAR(o.fx, ref.fx, 1e-6 * muFz) << steps;
      EXPECT_NEAR(o.fy, ref.fy, 1e-6 * muFz) << steps;
      EXPECT_NEAR(o.mz, ref.mz, 1e-6 * std::abs(ref.mz)) << steps;
    }
}

TEST(TransientFastSim, LanesByDefaultFromFourNodesAStrip) {
  TransientState s;
  const bool lanes = stripLanesAvailable();
  EXPECT_FALSE(s.marchesInLanes(TransientState::kLanesFromNodes - 1));
  EXPECT_EQ(s.marchesInLanes(TransientState::kLanesFromNodes), lanes);
  s.setStripLanes(TransientState::StripLanes::kOn);
  EXPECT_EQ(s.marchesInLanes(2), lanes);
  s.setStripLanes(TransientState::StripLanes::kOff);
  EXPECT_FALSE(s.marchesInLanes(40));
}
