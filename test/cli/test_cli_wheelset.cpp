// contact_cli wheelset: its --config (the wheelset and track keys beside the model's parameters)
// and the command itself on the Manchester benchmark's case.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "../../src/cli/cli.hpp"
#include "../../src/cli/config_yaml.hpp"

using namespace wheel_rail_contact;

namespace {

std::string writeTemp(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + name;
  std::ofstream(path) << text;
  return path;
}

std::string configErrorOf(const std::string& yaml) {
  ContactParameters p;
  WheelsetConfig w;
  try {
    loadWheelsetConfigYaml(writeTemp("wbad.yaml", yaml), &p, &w);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace

TEST(WheelsetConfig, KeysGoToTheTrackTheProfileReaderAndTheParameters) {
  const std::string f = writeTemp("w.yaml",
                                  "nominal_radius: 0.45\nflange_back_distance: 1.36\n"
                                  "flange_back_position: -0.07\ngauge: 1.432\ngauge_depth: 0.015\n"
                                  "rail_inclination: 0.025\ncant: 0.01\n"
                                  "profile_length_unit: mm\nprofile_lateral_axis: toward_gauge\n"
                                  "profile_vertical_axis: up\nprofile_smoothing_length: 5e-4\n"
                                  "mu: 0.25\nmodel: steady\nframe_id: left\n");
  ContactParameters p;
  WheelsetConfig w;
  loadWheelsetConfigYaml(f, &p, &w);
  EXPECT_EQ(w.track.nominal_radius, 0.45);
  EXPECT_EQ(w.track.flange_back_distance, 1.36);
  EXPECT_EQ(w.track.flange_back_position, -0.07);
  EXPECT_EQ(w.track.gauge, 1.432);
  EXPECT_EQ(w.track.gauge_depth, 0.015);
  EXPECT_EQ(w.track.rail_inclination, 0.025);
  EXPECT_EQ(w.track.cant, 0.01);
  EXPECT_EQ(w.profile_read.length_unit, 1e-3);
  EXPECT_EQ(w.profile_read.lateral, LateralAxis::kTowardGauge);
  EXPECT_EQ(w.profile_read.vertical, VerticalAxis::kUp);
  EXPECT_EQ(w.profile_read.smoothing_length, 5e-4);
  EXPECT_EQ(p.mu, 0.25);
  EXPECT_EQ(p.model, "steady");
}

TEST(WheelsetConfig, DefaultsAreTheBenchmarksAndDocumented) {
  const WheelsetConfig w;
  const WheelsetTrackData d;
  EXPECT_EQ(w.track.gauge, d.gauge);
  EXPECT_EQ(w.profile_read.length_unit, 0.0);  // the file says
  for (const ParameterDoc& doc : wheelsetParameterDocs()) {
    WheelsetConfig set;
    if (doc.default_value == "file") continue;
    EXPECT_TRUE(setWheelsetParameter(&set, doc.name, doc.default_value)) << doc.name;
  }
  WheelsetConfig set;
  EXPECT_FALSE(setWheelsetParameter(&set, "mu", "0.3"));
}

TEST(WheelsetConfig, ErrorsNameTheKeyAndTheFile) {
  EXPECT_EQ(configErrorOf("gauge: wide\n").rfind("gauge: expected a finite number, got 'wide'", 0),
            0u);
  EXPECT_EQ(configErrorOf("cant: .nan\n").rfind("cant: expected a finite number", 0), 0u);
  EXPECT_EQ(configErrorOf("profile_length_unit: -1\n").rfind("profile_length_unit: must be > 0", 0),
            0u);
  EXPECT_EQ(configErrorOf("profile_lateral_axis: left\n").rfind("profile_lateral_axis:", 0), 0u);
  EXPECT_EQ(configErrorOf("profile_vertical_axis: z\n").rfind("profile_vertical_axis:", 0), 0u);
  EXPECT_EQ(configErrorOf("guage: 1.435\n").rfind("guage: unknown parameter", 0), 0u);
  EXPECT_NE(configErrorOf("gauge: wide\n").find("(in '"), std::string::npos);
  EXPECT_EQ(configErrorOf(""), "(no error)");
}
