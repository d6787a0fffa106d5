/// Landmarks of a profile that place it in the track: a rail's top and gauge point, a wheel's
/// flange tip; and a rail turned by its inclination.
#pragma once

#include <Eigen/Core>

#include "wheel_rail_contact/profiles/profile.hpp"

namespace wheel_rail_contact {

/// The profile's extreme point in z (the highest for a rail, the lowest for a wheel), profile
/// frame. *at_end: the extreme is an end of the profile (axes the wrong way up).
struct ProfileExtreme {
  double s = 0.0;
  Eigen::Vector2d position = Eigen::Vector2d::Zero();
  bool at_end = false;
};
ProfileExtreme profileExtreme(const Profile& profile);

/// The gauge-side (largest y) point where the profile crosses the height z_level. False if it
/// does not cross it.
bool gaugeSideCrossing(const Profile& profile, double z_level, Eigen::Vector2d* point);

/// The profile turned about the frame's origin by `angle` (counter-clockwise in y_p-z_p). The
/// smoothing spline's fit does not depend on the axes, so this is the same curve turned.
Profile rotatedProfile(const Profile& profile, double angle);

}  // namespace wheel_rail_contact
