/// Wheelset scenario files: the wheelset states contact_cli wheelset replays, one row per time
/// step.
///
/// CSV, SI units, the track's REP 103 axes (x forward, y left, z up). A header names the columns,
/// in any order: t,y,yaw,roll,V,omega and either fz (the vertical load on each wheel) or
/// fz_left,fz_right; optionally vy,yaw_rate,curvature and vz,roll_rate (0 when not given) and cant
/// (the caller's default when not given).
///   t [s] (strictly increasing), y [m] lateral displacement of the wheelset's centre, positive to
///   the left; yaw [rad] about z, positive turns the leading end to the left; roll [rad] about the
///   yawed wheelset's x, positive raises the left wheel; V [m/s] forward speed; omega [rad/s] the
///   pitch rate about the axle, about V / r0 > 0 when rolling forward; fz, fz_left, fz_right [N]
///   vertical load per wheel; vy [m/s] lateral velocity; yaw_rate [rad/s]; curvature [1/m] of
///   the track, positive for a curve to the left; cant [rad] of the track under the wheelset,
///   positive raises the left rail (WheelsetMotion::cant: checked by the step, not here); vz
///   [m/s] vertical velocity and roll_rate [rad/s] (WheelsetMotion: what makes the motion follow
///   the profiles while y changes).
/// An unknown or repeated column, a missing one, a field that is not a finite number, or t not
/// increasing is refused with "source:line: reason". Lines starting with '#' are comments.
#pragma once

#include <istream>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace wheel_rail_contact {

struct WheelsetScenarioRow {
  double t = 0.0;          ///< [s]
  double y = 0.0;          ///< [m]
  double yaw = 0.0;        ///< [rad]
  double roll = 0.0;       ///< [rad]
  double V = 0.0;          ///< [m/s]
  double omega = 0.0;      ///< [rad/s]
  double fz_left = 0.0;    ///< [N]
  double fz_right = 0.0;   ///< [N]
  double vy = 0.0;         ///< [m/s]
  double yaw_rate = 0.0;   ///< [rad/s]
  double curvature = 0.0;  ///< [1/m]
  /// [rad]; empty when the scenario has no cant column (contact_cli wheelset: its --config's cant)
  std::optional<double> cant;
  double vz = 0.0;         ///< [m/s]
  double roll_rate = 0.0;  ///< [rad/s]
};

/// A malformed wheelset scenario: what() is "source:line: reason".
class WheelsetScenarioError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Reads a whole wheelset scenario; `source` names the input in messages. Throws
/// WheelsetScenarioError.
std::vector<WheelsetScenarioRow> readWheelsetScenario(std::istream& in, const std::string& source);

}  // namespace wheel_rail_contact
