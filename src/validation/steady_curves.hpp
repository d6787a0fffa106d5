/// The cached exact steady creep curves (doc/data/steady_exact_curves.csv, written by
/// identify_calibration): one point per line, a_over_b,ray,epsilon,xi,eta,phi,fx,fy,mz with fx, fy
/// over mu fz and mz over mu fz sqrt(ab) (the setup is in the file's comment lines).
#pragma once

#include <string>
#include <vector>

#include "core/fastsim/fastsim.hpp"

namespace wheel_rail_contact {

struct SteadyCurvePoint {
  double aOverB = 0.0;
  std::string ray;     ///< 11, 22, 23 (one creepage) or a combination (identify_calibration.cpp)
  double epsilon = 0;  ///< normalised creepage (calibration_table.hpp)
  Creepages c;
  double fx = 0.0, fy = 0.0, mz = 0.0;
};

/// The cache's header line, its columns in order: written by identify_calibration, required here.
inline constexpr const char* kSteadyCurvesHeader = "a_over_b,ray,epsilon,xi,eta,phi,fx,fy,mz";

/// The points of `path` in file order; none if the file does not exist or is empty. Throws
/// std::runtime_error naming the file and line where the first line that is not a comment is not
/// kSteadyCurvesHeader (other or more columns are refused, not ignored), where a line has other
/// than its 9 fields, or where a field is not a finite number.
std::vector<SteadyCurvePoint> readSteadyCurves(const std::string& path);

}  // namespace wheel_rail_contact
