/// Wheel and rail profiles read from a file, checked, and interpolated by a smoothing spline.
///
/// Units: SI (m) once read, whatever the file's unit. Every profile is held in its *profile
/// frame*, the same for wheels and rails and for both sides of the track:
///   - y_p lateral, positive toward the track centre (the gauge side: toward the flange on a wheel,
///     toward the gauge face on a rail);
///   - z_p vertical, positive up (away from the rail's foot; for a wheel, toward the axle);
///   - the origin as in the file.
/// For the right wheel and rail, REP 103's track axes (x forward, y left, z up) and the profile
/// frame have y and z alike; the left side is the mirror image (doc/profiles.md). The Simpack and
/// CONTACT files of the Manchester benchmark have y toward the field side and z down, the profile
/// frame turned half a turn about x: y_p = -y_file, z_p = -z_file (ProfileReadOptions's default).
///
/// Interpolation: a cubic smoothing spline of y_p and z_p, each a function of the chord length s
/// along the points. A parametric curve because profiles have vertical and overhanging flanks
/// (flange back, gauge face) where z(y) is not a function; the chord length because it is close
/// to the arc length, so the parameter's speed stays near 1 and slopes and curvatures are well
/// conditioned everywhere. A smoothing spline (it minimises sum_i w_i |p_i - f(s_i)|^2 + lambda
/// integral |f''(s)|^2 ds, w_i the arc length each point stands for) rather than an interpolating
/// one because a measured profile's noise of a few micrometres at 0.1 mm spacing gives curvatures
/// of 100 1/m and more under interpolation, against 1/0.3 m on a rail crown; the contact angle and
/// curvature feed the contact patch directly. Cubic because the curvature is then continuous. With
/// the weights per arc length, lambda = L^4 makes the smoothing independent of the point spacing:
/// L (smoothing_length) is a length, and features shorter than about 2 pi L are damped (the
/// spline's transfer function is 1 / (1 + (k L)^4) at wavenumber k).
#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

namespace wheel_rail_contact {

enum class ProfileKind { kRail, kWheel };

/// Direction of a file's first (lateral) column, seen on the profile's own side of the track.
enum class LateralAxis {
  kTowardField,  ///< positive away from the track centre (Simpack, CONTACT for the right side)
  kTowardGauge   ///< positive toward the track centre (our profile frame)
};
/// Direction of a file's second (vertical) column.
enum class VerticalAxis {
  kDown,  ///< positive down (Simpack, CONTACT)
  kUp     ///< positive up (our profile frame)
};

/// Default smoothing length L [m]: 0.1 mm. It damps features shorter than about 0.6 mm, i.e. a
/// profile gauge's point-to-point noise, and moves the benchmark's S1002 and UIC60 (exact shapes,
/// printed to 1e-6 mm) by less than 0.1 micrometre, far below the elastic approach of a loaded
/// wheel (tens of micrometres) that the gap functions feed. A measured profile's noise wants more,
/// about 0.5 mm (doc/profiles.md).
constexpr double kDefaultProfileSmoothingLength = 1.0e-4;

struct ProfileReadOptions {
  /// Metres per file unit (1e-3 for mm). 0: the file says: a Simpack file's units.len.f, or in a
  /// text file a comment line "# unit: mm" (or m) or a header with columns named like y_mm,z_mm or
  /// "y [mm]". A unit given both here and in the file must agree. No unit at all is an error.
  double length_unit = 0.0;
  /// The file's axes (for Simpack files too, after the file's own mirror.y/mirror.z), mapped onto
  /// the profile frame. The defaults are Simpack's and CONTACT's.
  LateralAxis lateral = LateralAxis::kTowardField;
  VerticalAxis vertical = VerticalAxis::kDown;
  double smoothing_length = kDefaultProfileSmoothingLength;  ///< L >= 0 [m]; 0 interpolates
  /// Consecutive points closer than this are refused as duplicates [m]. 1 nm: the last digit of a
  /// file printed in mm to eight significant digits, far below a profile gauge's resolution.
  double min_point_distance = 1.0e-9;
  /// Consecutive points farther apart than this are refused as a hole in the profile [m].
  double max_point_distance = 5.0e-3;
};

/// Fewest points a profile may have.
constexpr int kMinProfilePoints = 10;

/// A wheel or rail profile. Immutable once built; cheap to share (std::shared_ptr<const Profile>).
class Profile {
 public:
  /// Reads a profile file: Simpack's .prw/.prr (recognised by its header.begin/spline.begin
  /// blocks, whatever the file's name) or plain text/CSV with two columns, lateral and vertical,
  /// separated by commas, semicolons or white space (an optional third column is a weight, as in
  /// Simpack's point list). Lines starting with #, % or ! are comments; one header line of column
  /// names may precede the numbers. Refuses a file that does not parse or whose points are not a
  /// profile (fewer than kMinProfilePoints, not finite, duplicate or too close, too far apart,
  /// turning back on themselves, crossing themselves) with std::runtime_error "file:line: reason".
  static Profile read(const std::string& path, ProfileKind kind,
                      const ProfileReadOptions& options = {});
  /// As read(), from the file's text; `name` stands for the file in messages.
  static Profile parse(const std::string& text, const std::string& name, ProfileKind kind,
                       const ProfileReadOptions& options = {});
  /// From points already in the profile frame (m), in order along the profile; checked as a file.
  static Profile fromPoints(const std::vector<Eigen::Vector2d>& points, ProfileKind kind,
                            const std::string& name,
                            double smoothing_length = kDefaultProfileSmoothingLength);

  /// The Manchester benchmark's S1002 wheel and UIC60 rail with its 1:40 inclination built in,
  /// compiled into the library, read with the default options.
  static std::shared_ptr<const Profile> standardWheel();
  static std::shared_ptr<const Profile> standardRail();

  /// A point of the spline at parameter s in [0, length()] (clamped).
  struct Point {
    Eigen::Vector2d position;  ///< profile frame [m]
    Eigen::Vector2d tangent;   ///< unit, toward increasing s (overall toward the track centre)
    Eigen::Vector2d normal;    ///< unit, out of the material: up-ish on a rail, down-ish on a wheel
    /// 1/radius [1/m] in the profile's plane: positive where the surface is convex (rail crown,
    /// flange tip), negative where it is concave (flange root).
    double curvature = 0.0;
  };
  Point at(double s) const;
  /// The parameter's range [0, length()]: the chord length along the points [m].
  double length() const;
  /// Every s at which the spline crosses the lateral coordinate y (profile frame), in increasing
  /// order; none if y is outside the profile.
  std::vector<double> crossings(double y) const;
  /// The surface seen from outside the material at lateral coordinate y: a rail's highest crossing,
  /// a wheel's lowest. False if the profile does not reach y.
  bool surfaceAt(double y, double* z, double* s) const;
  /// Lateral extent of the spline [m].
  double yMin() const { return y_min_; }
  double yMax() const { return y_max_; }

  /// The file's own coordinates (m, the file's axes, after a Simpack file's own processing) of a
  /// point of the profile frame, and back.
  Eigen::Vector2d toFile(const Eigen::Vector2d& p) const;
  Eigen::Vector2d fromFile(const Eigen::Vector2d& q) const;

  ProfileKind kind() const { return kind_; }
  const std::string& name() const { return name_; }
  double smoothingLength() const { return smoothing_length_; }
  /// The points as read, in the profile frame (m), in order of increasing s.
  const std::vector<Eigen::Vector2d>& points() const { return points_; }

  Profile(const Profile&);
  Profile& operator=(const Profile&);
  Profile(Profile&&) noexcept;
  Profile& operator=(Profile&&) noexcept;
  ~Profile();

 private:
  Profile();
  struct Impl;
  std::unique_ptr<Impl> impl_;
  ProfileKind kind_ = ProfileKind::kRail;
  std::string name_;
  double smoothing_length_ = 0.0;
  double file_sign_y_ = 1.0, file_sign_z_ = 1.0;
  double y_min_ = 0.0, y_max_ = 0.0;
  std::vector<Eigen::Vector2d> points_;

  friend struct ProfileBuilder;
};

}  // namespace wheel_rail_contact
