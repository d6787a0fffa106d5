/// Wheelset and track data: what places the wheel and rail profiles relative to each other.
///
/// Axes: REP 103 track axes, x forward, y left, z up; the origin on the track centre line in the
/// plane of the rails' tops. Units SI (m, rad). The track's cant (the rails' plane turned about x)
/// is not track data: it changes along the track, and each step gives the cant under the
/// wheelset (WheelsetMotion::cant). The geometry here is relative to the rails' plane, so the cant
/// does not change it.
#pragma once

#include <memory>

#include "wheel_rail_contact/profiles/profile.hpp"

namespace wheel_rail_contact {

struct WheelsetTrackData {
  /// Rolling radius where the wheel profile's file has z = 0 [m] (the benchmark's S1002 has z = 0
  /// on its taping line, 70 mm from the flange back).
  double nominal_radius = 0.46;
  /// Distance between the two wheels' flange backs (inner faces) [m].
  double flange_back_distance = 1.360;
  /// Lateral coordinate of the flange back in the wheel profile file's own coordinates [m], as a
  /// multibody code's input names it (the benchmark's: -70 mm on its S1002, whose y runs to the
  /// field side). Need not be a point of the profile.
  double flange_back_position = -0.070;
  /// Track gauge [m], between the rails' gauge faces at gauge_depth below the top of the rails.
  double gauge = 1.435;
  double gauge_depth = 0.014;  ///< [m]
  /// Inclination (tangent of the angle) by which the rail profiles are tilted toward the track
  /// centre, 1/40 = 0.025. 0: as read, which is right for a profile with its inclination built in
  /// (the standard UIC60 1:40).
  double rail_inclination = 0.0;
  /// Profiles in their profile frame (profile.hpp). Null right profiles: the standard S1002 and
  /// UIC60 1:40 (Profile::standardWheel(), standardRail()). Null left profiles: the right ones
  /// mirrored.
  std::shared_ptr<const Profile> wheel_right, wheel_left, rail_right, rail_left;

  /// Throws std::invalid_argument naming the parameter if a value is outside its physical range
  /// or the profiles cannot be placed with it: nominal_radius (0.1, 1] m; flange_back_distance
  /// [0.5, 2] m and below gauge; gauge [0.5, 2] m; gauge_depth (0, 0.05] m; rail_inclination
  /// [0, 0.1]; flange_back_position finite and within 20 mm of the wheel
  /// profile's lateral extent; a profile of the wrong kind; a rail whose highest point, or a wheel
  /// whose lowest point (the flange tip), is an end of the profile (axes upside down); a rail that
  /// does not reach gauge_depth below its top on the gauge side; a wheel whose flange tip is not
  /// between its tread and the flange back (lateral axis reversed).
  void validate() const;
};

}  // namespace wheel_rail_contact
