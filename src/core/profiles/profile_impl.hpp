/// Internals of Profile shared by its reader and its queries.
#pragma once

#include <Eigen/Core>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/profiles/smoothing_spline.hpp"
#include "wheel_rail_contact/profiles/profile.hpp"

namespace wheel_rail_contact {

struct Profile::Impl {
  SmoothingSpline2d spline;
  /// Parameter values splitting the spline into pieces on which y(s) is monotone.
  std::vector<double> piece_t;
  std::vector<double> piece_y;  ///< y at piece_t
};

/// Refuses a profile: std::runtime_error "name:line: reason" (no line where line <= 0).
[[noreturn]] inline void refuse(const std::string& name, int line, const std::string& reason) {
  std::ostringstream os;
  os << name;
  if (line > 0) os << ':' << line;
  os << ": " << reason;
  throw std::runtime_error(os.str());
}

/// A point as read, in the profile frame (m) once converted, with its line in the file.
struct ProfileSourcePoint {
  Eigen::Vector2d p;
  double weight = 1.0;
  int line = 0;
};

/// Builds Profiles: the checks every source of points goes through, then the spline.
struct ProfileBuilder {
  /// Checks the points (count, finite, spacing, turning back, crossing) and refuses them with
  /// std::runtime_error "name:line: reason"; orders them toward the track centre; fits the spline.
  static Profile build(std::vector<ProfileSourcePoint> points, ProfileKind kind,
                       const std::string& name, double smoothing_length, double min_point_distance,
                       double max_point_distance, double file_sign_y, double file_sign_z);
};

}  // namespace wheel_rail_contact
