// The Manchester benchmark's case as WheelsetContact's inputs: the right-wheel rows at 0.5,
// 5, 5.5 and 6.5 mm of test/data/profiles/a22_cases.csv (tread, gauge corner, corner, flange),
// shared by the WheelsetContact tests (tests only).
#pragma once

#include <utility>
#include <vector>

#include "wheel_rail_contact/wheelset/wheelset_contact.hpp"

namespace a22_wheelset {

using wheel_rail_contact::WheelsetState;

/// The benchmark's right-wheel state at lateral shift y_mm (CONTACT's axes: to the right) in our
/// REP 103 axes (doc/profiles.md): y and yaw change sign, roll does not; omega = -vpitch.
inline WheelsetState a22(double y_mm, double yaw, double roll, double vpitch) {
  WheelsetState s;
  s.pose.y = -y_mm * 1e-3;
  s.pose.yaw = -yaw;
  s.pose.roll = roll;
  s.motion.V = 2.0;
  s.motion.omega = -vpitch;
  s.fz_left = s.fz_right = 1e4;
  return s;
}
inline WheelsetState tread() {
  return a22(0.5, 0.0012, -2.304e-05, -4.34741);
}
inline WheelsetState corner() {
  return a22(5.0, 0.012, -0.0003554, -4.33536);
}
inline WheelsetState corner2() {
  return a22(5.5, 0.0132, -0.0004777, -4.33189);
}
inline WheelsetState flange() {
  return a22(6.5, 0.0156, -0.004376, -4.27488);
}
/// The four above, tread to flange.
inline std::vector<WheelsetState> fourStates() {
  return {tread(), corner(), corner2(), flange()};
}

/// The mirror image in the track's x-z plane: the left wheel then sees what the right one saw.
inline WheelsetState mirrored(WheelsetState s) {
  s.pose.y = -s.pose.y;
  s.pose.yaw = -s.pose.yaw;
  s.pose.roll = -s.pose.roll;
  s.motion.vy = -s.motion.vy;
  s.motion.yaw_rate = -s.motion.yaw_rate;
  s.motion.curvature = -s.motion.curvature;
  s.motion.cant = -s.motion.cant;
  std::swap(s.fz_left, s.fz_right);
  return s;
}

}  // namespace a22_wheelset
