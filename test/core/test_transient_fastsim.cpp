#include <gtest/gtest.h>

#include <cmath>

#include "wheel_rail_contact/transient_fastsim.hpp"

using namespace wheel_rail_contact;

namespace {
TransientState linearField(const PatchMesh& m) {  // tau_x = x, tau_y = 2 y (in metres)
  TransientState s;
  s.resize(m.size());
  for (int j = 0; j < m.ny(); ++j)
    for (int i = 0; i < m.nx(); ++i) {
      s.tx(m.index(i, j)) = m.nodeX(i, j);
      s.ty(m.index(i, j)) = 2.0 * m.stripY(j);
      s.sx(m.index(i, j)) = 1.0;
    }
  return s;
}
}  // namespace

TEST(RemapState, SamePatchIsTheIdentity) {
  const PatchMesh m(12, 10, 6e-3, 4e-3);
  const TransientState in = linearField(m);
  TransientState out;
  remapState(m, in, m, &out);
  EXPECT_LT((out.tx - in.tx).abs().maxCoeff(), 1e-15);
  EXPECT_LT((out.ty - in.ty).abs().maxCoeff(), 1e-15);
  EXPECT_LT((out.sx - in.sx).abs().maxCoeff(), 1e-12);
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
      EXPECT_NEAR(out.tx(small.index(i, j)), small.nodeX(i, j), 2e-5) << i << "," << j;
      EXPECT_NEAR(out.ty(small.index(i, j)), 2.0 * small.stripY(j), 1e-12) << i << "," << j;
    }
}

TEST(RemapState, GrowingPatchGivesZeroOutsideTheOldOne) {
  const PatchMesh m(10, 10, 6e-3, 4e-3);
  PatchMesh grown = m;
  grown.scale(2 * 6e-3, 2 * 4e-3);
  TransientState in;
  in.resize(m.size());
  in.tx.setConstant(5.0);
  TransientState out;
  remapState(m, in, grown, &out);
  EXPECT_EQ(out.tx(grown.index(0, 5)), 0.0);  // leading node of the grown patch lies outside
  EXPECT_EQ(out.tx(grown.index(5, 0)), 0.0);  // outer strip lies outside
  EXPECT_NEAR(out.tx(grown.index(5, 5)), 5.0, 1e-12);
  EXPECT_LE(out.tx.maxCoeff(), 5.0 + 1e-12);
}
