#include "wheel_rail_contact/profiles/wheelset_track.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

#include "core/profiles/placement.hpp"

namespace wheel_rail_contact {

namespace {

[[noreturn]] void bad(const std::string& parameter, const std::string& why) {
  throw std::invalid_argument("WheelsetTrackData: " + parameter + " " + why);
}

void inRange(const char* name, double v, double lo, double hi, bool lo_open, const char* unit) {
  const bool ok = std::isfinite(v) && (lo_open ? v > lo : v >= lo) && v <= hi;
  if (!ok) {
    std::ostringstream os;
    os << "= " << v << " is outside " << (lo_open ? "(" : "[") << lo << ", " << hi << "] " << unit;
    bad(name, os.str());
  }
}

void checkRail(const char* name, const Profile& rail, const WheelsetTrackData& d) {
  if (rail.kind() != ProfileKind::kRail) bad(name, "is a wheel profile");
  const Profile turned = rotatedProfile(rail, -std::atan(d.rail_inclination));
  const ProfileExtreme top = profileExtreme(turned);
  if (top.at_end)
    bad(name,
        "(" + rail.name() +
            "): its highest point is an end of the profile; is its vertical axis upside down?");
  Eigen::Vector2d g;
  if (!gaugeSideCrossing(turned, top.position.y() - d.gauge_depth, &g) || g.x() <= top.position.x())
    bad(name, "(" + rail.name() + ") does not reach gauge_depth below its top on the gauge side");
}

void checkWheel(const char* name, const Profile& wheel, const WheelsetTrackData& d) {
  if (wheel.kind() != ProfileKind::kWheel) bad(name, "is a rail profile");
  const ProfileExtreme tip = profileExtreme(wheel);
  if (tip.at_end)
    bad(name,
        "(" + wheel.name() +
            "): its lowest point is an end of the profile; is its vertical axis upside down?");
  const double fb = wheel.fromFile(Eigen::Vector2d(d.flange_back_position, 0.0)).x();
  if (fb < wheel.yMin() - 0.02 || fb > wheel.yMax() + 0.02)
    bad("flange_back_position", "is more than 20 mm outside the wheel profile " + wheel.name());
  if (fb <= tip.position.x())
    bad("flange_back_position", "lies on the tread's side of the flange tip of " + wheel.name() +
                                    ": is the profile's lateral axis reversed?");
}

}  // namespace

void WheelsetTrackData::validate() const {
  inRange("nominal_radius", nominal_radius, 0.1, 1.0, true, "m");
  inRange("flange_back_distance", flange_back_distance, 0.5, 2.0, false, "m");
  inRange("gauge", gauge, 0.5, 2.0, false, "m");
  if (!(flange_back_distance < gauge)) bad("flange_back_distance", "must be smaller than gauge");
  inRange("gauge_depth", gauge_depth, 0.0, 0.05, true, "m");
  inRange("rail_inclination", rail_inclination, 0.0, 0.1, false, "(tangent)");
  if (!std::isfinite(flange_back_position)) bad("flange_back_position", "is not finite");
  const std::shared_ptr<const Profile> wr = wheel_right ? wheel_right : Profile::standardWheel();
  const std::shared_ptr<const Profile> rr = rail_right ? rail_right : Profile::standardRail();
  checkWheel("wheel_right", *wr, *this);
  if (wheel_left) checkWheel("wheel_left", *wheel_left, *this);
  checkRail("rail_right", *rr, *this);
  if (rail_left) checkRail("rail_left", *rail_left, *this);
}

}  // namespace wheel_rail_contact
