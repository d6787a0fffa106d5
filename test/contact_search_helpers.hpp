// What the contact search's and the creepages' tests share: the mirrored pose and the closest
// candidate (tests only).
#pragma once

#include <gtest/gtest.h>

#include "wheel_rail_contact/profiles/contact_search.hpp"

namespace wheel_rail_contact {

/// The mirror image of a pose in the track's x-z plane (the left wheel's view of the right's).
inline WheelsetPose mirrored(const WheelsetPose& p) {
  WheelsetPose m = p;
  m.y = -p.y;
  m.yaw = -p.yaw;
  m.roll = -p.roll;
  return m;
}

/// The closest candidate of a search that must have found one. A copy: callers pass the search's
/// result as a temporary, which a reference would outlive.
inline ContactCandidate closest(const WheelContactGeometry& g) {
  EXPECT_EQ(g.status, ContactSearchStatus::kOk) << g.message;
  EXPECT_GE(g.closest, 0);
  return g.candidates.at(g.closest);
}

}  // namespace wheel_rail_contact
