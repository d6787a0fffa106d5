/// Contact search between a wheelset's wheels and the rails: the geometry only (where the profiles
/// touch or overlap, the contact angle, the rolling radius, the undeformed gap across each
/// candidate patch). No forces.
///
/// Axes: REP 103 track axes as in wheelset_track.hpp (x forward, y left, z up, origin on the
/// track centre line in the plane of the rails' tops). Units SI.
///
/// Method. Each wheel is a surface of revolution about the axle, each rail a prism along x. Two
/// such surfaces touch where their normals are parallel, so the rail's normal, having no
/// x-component, means the wheel's has none either: for every circle of the wheel (one point s of
/// its profile) the search takes the one point whose normal lies in the track's y-z plane. That
/// point is exact for any yaw and roll (not a first-order shift): with yaw psi and a contact
/// angle delta it sits about r tan(delta) sin(psi) ahead of or behind the axle (ContactCandidate::
/// lead), which on a flange at 10 mrad is some 10 mm. The locus of these points, seen in the
/// y-z plane, faces the rail, and the vertical distance from it down to the rail's surface is the
/// vertical gap g(s). Where g has a local minimum the profiles' tangents are parallel: each one is
/// a contact candidate, whatever the vertical position (which shifts g as a whole). A circle with
/// no point facing the y-z plane (a steep flank under large yaw) takes no part.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "wheel_rail_contact/profiles/wheelset_track.hpp"

namespace wheel_rail_contact {

enum class WheelSide { kLeft, kRight };

/// Where on the wheel a candidate lies, by its contact angle (ContactSearchOptions).
enum class ContactZone { kTread, kGaugeCorner, kFlange };

/// The wheelset's position relative to the track (REP 103 axes).
struct WheelsetPose {
  double y = 0.0;  ///< lateral displacement of the wheelset's centre [m], positive to the left
  /// Vertical displacement [m], positive up; 0: the axle nominal_radius above the rails' plane.
  double z = 0.0;
  double yaw = 0.0;   ///< about the track's z [rad], positive turns the leading end to the left
  double roll = 0.0;  ///< about the yawed wheelset's x [rad], positive raises the left wheel
};

/// The undeformed gap at one lateral position of a candidate's contact plane.
struct GapSample {
  double eta = 0.0;  ///< lateral coordinate in the contact plane from the contact point [m]
  double gap = 0.0;  ///< distance along the contact normal, rail to wheel [m]; < 0: overlap
  /// The wheel at this eta: its circle's radius [m] and the angle of its normal from the track's
  /// z axis [rad] (sign as ContactCandidate::contact_angle). The wheel's curvature along the
  /// rolling direction there is cos(contact_angle) / rolling_radius (Meusnier).
  double rolling_radius = 0.0;
  double contact_angle = 0.0;
};

/// One local minimum of the gap between a wheel and its rail.
struct ContactCandidate {
  ContactZone zone = ContactZone::kTread;
  /// Undeformed distance from the rail's contact point along its normal to the wheel [m];
  /// negative where the undeformed profiles overlap (the approach the patch must take up).
  double gap = 0.0;
  double vertical_gap = 0.0;  ///< the same measured vertically [m]
  /// Angle of the contact normal from the track's z axis [rad], positive when the rail pushes the
  /// wheel toward the track centre (flange contact: large and positive).
  double contact_angle = 0.0;
  double rolling_radius = 0.0;  ///< radius of the wheel's circle through the contact point [m]
  /// The contact point on the rail, track axes [m]. Its x includes the wheel's own shift under
  /// yaw (-y_W sin(yaw) for a wheel y_W from the wheelset's centre); see lead.
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  /// How far the contact point lies ahead (+x) of its wheel circle's centre [m]: about
  /// -r tan(contact_angle) sin(yaw) on the right wheel, +r tan(contact_angle) sin(yaw) on the
  /// left; ahead on a wheel that the yaw steers into its rail.
  double lead = 0.0;
  /// Unit contact normal in the track's y-z plane (y, z), from the rail into the wheel.
  Eigen::Vector2d normal = Eigen::Vector2d::UnitY();
  /// The contact point on the rail and on the wheel in the profile files' own coordinates (m, as
  /// read; a mirrored left profile gives those of the right-side file it mirrors).
  Eigen::Vector2d rail_file = Eigen::Vector2d::Zero();
  Eigen::Vector2d wheel_file = Eigen::Vector2d::Zero();
  double s_rail = 0.0, s_wheel = 0.0;  ///< the profiles' spline parameters [m]
  /// Undeformed gap across the candidate, eta along the contact plane's lateral direction,
  /// positive toward the track centre, from the point of the smallest vertical gap (eta = 0 gives
  /// `gap`). Sampled where the gap stays below gap + max(2 max(|gap|, gap_window), gap_reach)
  /// (ContactSearchOptions), and not beyond the ridge separating the candidate from its
  /// neighbours nor beyond max_gap_extent either side.
  std::vector<GapSample> gap_function;
};

enum class ContactSearchStatus {
  kOk,            ///< candidates found
  kInvalidInput,  ///< a pose value not finite or beyond the search's range (message)
  kOutOfRange,    ///< no candidate: the wheel is not above its rail, or the smallest gap is at a
                  ///< profile's end (message)
};

struct WheelContactGeometry {
  ContactSearchStatus status = ContactSearchStatus::kOk;
  std::string message;
  /// Candidates in order from the field side to the flange; those with gap < 0 overlap.
  std::vector<ContactCandidate> candidates;
  int closest = -1;  ///< index of the candidate with the smallest vertical gap, -1 if none
};

struct ContactSearchOptions {
  /// Spacing of the circles of the wheel profile the search samples before refining each minimum
  /// [m]. Minima closer together than this can merge.
  double sample_spacing = 1.0e-4;
  /// Two minima of the gap are separate candidates only if the gap rises by at least this between
  /// them [m]: a lower ridge is flattened by the first micrometre of elastic approach, and the two
  /// make one patch.
  double min_ridge = 1.0e-6;
  /// Candidates whose vertical gap exceeds the smallest by more than this are left out [m].
  double candidate_window = 1.0e-3;
  double gap_window = 1.0e-5;  ///< see ContactCandidate::gap_function [m]
  /// How far above its minimum the gap function reaches at least [m]: the normal problem's
  /// approach (normal/patch_normal.hpp) needs the gap up to that approach; 10 kN on a wheel takes
  /// some 0.05 to 0.1 mm, twice the load some 0.15 mm, so 0.4 mm leaves room for a heavy load.
  double gap_reach = 4.0e-4;
  double max_gap_extent = 0.03;  ///< farthest the gap function reaches either side of eta = 0 [m]
  int gap_samples = 81;          ///< points of each gap function (odd: one at eta = 0)
  /// Contact-angle limits of the zones [rad]: tread below tread_max_angle, flange from
  /// flange_min_angle, gauge corner between. A tread's cone has a few degrees, the throat where
  /// it turns into the flange meets the rail's gauge corner at some 15 to 25 degrees, a flange's
  /// flank is 60 to 70 degrees at its steepest: 0.2 rad (11 degrees) and 0.6 rad (34 degrees)
  /// lie between.
  double tread_max_angle = 0.2;
  double flange_min_angle = 0.6;
  /// Poses beyond these are refused (status kInvalidInput).
  double max_abs_y = 0.05, max_abs_z = 0.05, max_abs_yaw = 0.1, max_abs_roll = 0.1;
};

/// Places the profiles (validated WheelsetTrackData) and searches a wheelset pose for contact.
class ContactSearch {
 public:
  /// Throws std::invalid_argument naming the parameter (WheelsetTrackData::validate(), options).
  explicit ContactSearch(const WheelsetTrackData& data, const ContactSearchOptions& options = {});

  /// The candidates of one wheel. Never throws on a pose; a bad one gives a status and a message.
  WheelContactGeometry search(WheelSide side, const WheelsetPose& pose) const;

  const WheelsetTrackData& data() const { return data_; }
  const ContactSearchOptions& options() const { return options_; }

  /// The rail's top (its highest point) and gauge point, track axes (y, z) [m].
  Eigen::Vector2d railTop(WheelSide side) const;
  Eigen::Vector2d gaugePoint(WheelSide side) const;

  ContactSearch(const ContactSearch&);
  ContactSearch& operator=(const ContactSearch&);
  ~ContactSearch();

 private:
  struct Side;
  WheelsetTrackData data_;
  ContactSearchOptions options_;
  std::vector<Side> sides_;  // [0] left, [1] right
};

}  // namespace wheel_rail_contact
