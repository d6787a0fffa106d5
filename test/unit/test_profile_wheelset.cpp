// Wheelset and track data: defaults and validation by parameter name.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>

#include "wheel_rail_contact/profiles/wheelset_track.hpp"

using namespace wheel_rail_contact;

namespace {

const std::string kDataDir = std::string(WRC_SOURCE_DIR) + "/config/profiles/";

std::string invalidMessage(const WheelsetTrackData& d) {
  try {
    d.validate();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(WheelsetTrack, DefaultsAreTheBenchmarks) {
  const WheelsetTrackData d;
  EXPECT_DOUBLE_EQ(d.nominal_radius, 0.46);
  EXPECT_DOUBLE_EQ(d.flange_back_distance, 1.360);
  EXPECT_DOUBLE_EQ(d.flange_back_position, -0.070);
  EXPECT_DOUBLE_EQ(d.gauge, 1.435);
  EXPECT_DOUBLE_EQ(d.gauge_depth, 0.014);
  EXPECT_EQ(d.rail_inclination, 0.0);  // built into the standard UIC60 1:40
  EXPECT_FALSE(d.wheel_right || d.wheel_left || d.rail_right || d.rail_left);
}

TEST(WheelsetTrack, ValidationNamesTheParameter) {
  auto with = [](auto change) {
    WheelsetTrackData d;
    change(d);
    return invalidMessage(d);
  };
  EXPECT_EQ(invalidMessage(WheelsetTrackData()), "");
  EXPECT_NE(with([](auto& d) { d.nominal_radius = 0.0; }).find("nominal_radius"),
            std::string::npos);
  EXPECT_NE(with([](auto& d) { d.nominal_radius = NAN; }).find("nominal_radius"),
            std::string::npos);
  EXPECT_NE(with([](auto& d) { d.flange_back_distance = 0.3; }).find("flange_back_distance"),
            std::string::npos);
  EXPECT_NE(with([](auto& d) { d.flange_back_distance = 1.5; }).find("flange_back_distance"),
            std::string::npos);
  EXPECT_NE(with([](auto& d) { d.gauge = 3.0; }).find("gauge"), std::string::npos);
  EXPECT_NE(with([](auto& d) { d.gauge_depth = 0.0; }).find("gauge_depth"), std::string::npos);
  EXPECT_NE(with([](auto& d) { d.rail_inclination = -0.025; }).find("rail_inclination"),
            std::string::npos);
  EXPECT_NE(with([](auto& d) { d.flange_back_position = INFINITY; }).find("flange_back_position"),
            std::string::npos);
  EXPECT_NE(with([](auto& d) { d.flange_back_position = -0.2; }).find("flange_back_position"),
            std::string::npos);
  EXPECT_NE(with([](auto& d) { d.wheel_left = Profile::standardRail(); }).find("wheel_left"),
            std::string::npos);
  EXPECT_NE(with([](auto& d) { d.rail_right = Profile::standardWheel(); }).find("rail_right"),
            std::string::npos);
  // A profile read with the wrong axes is caught: the rail upside down, the wheel reversed.
  ProfileReadOptions up;
  up.vertical = VerticalAxis::kUp;
  const std::string upside = with([&](auto& d) {
    d.rail_right = std::make_shared<const Profile>(
        Profile::read(kDataDir + "MBench_UIC60_v3.prr", ProfileKind::kRail, up));
  });
  EXPECT_NE(upside.find("rail_right"), std::string::npos) << upside;
  EXPECT_NE(upside.find("upside down"), std::string::npos) << upside;
  ProfileReadOptions reversed;
  reversed.lateral = LateralAxis::kTowardGauge;
  const std::string rev = with([&](auto& d) {
    d.wheel_right = std::make_shared<const Profile>(
        Profile::read(kDataDir + "MBench_S1002_v3.prw", ProfileKind::kWheel, reversed));
  });
  EXPECT_NE(rev.find("flange_back_position"), std::string::npos) << rev;
  EXPECT_NE(rev.find("reversed"), std::string::npos) << rev;
}
