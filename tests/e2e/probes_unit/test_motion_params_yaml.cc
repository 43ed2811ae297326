// Motion parameter files: values are read, mistakes name file, line and key.
#include <gtest/gtest.h>

#include <string>

#include "probes/trajectory/input_error.h"
#include "probes/trajectory/motion_params.h"
#include "temp_file.h"

namespace probes {
namespace {

std::string ErrorOf(const std::string& name, const std::string& text) {
  const std::string path = WriteTempFile(name, text);
  MotionParams p;
  try {
    LoadMotionParamsYaml(path, &p);
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no error for " << text;
  return {};
}

TEST(MotionParamsYaml, ReadsEveryKey) {
  const std::string path = WriteTempFile("good.yaml",
                                         "script: stir\n"
                                         "centre: [0.1, 0.2, 0.3]\n"
                                         "amplitude: 0.01\n"
                                         "depth: 0.02\n"
                                         "speed: 0.05\n"
                                         "duration: 7\n"
                                         "approach: 0.03\n"
                                         "hold: 0.2\n"
                                         "direction: [0, 1, 0]\n"
                                         "orientation: [0, 1, 0, 0]\n"
                                         "rate_hz: 500\n");
  MotionParams p;
  LoadMotionParamsYaml(path, &p);
  EXPECT_EQ(p.script, "stir");
  EXPECT_DOUBLE_EQ(p.centre[2], 0.3);
  EXPECT_DOUBLE_EQ(p.amplitude, 0.01);
  EXPECT_DOUBLE_EQ(p.depth, 0.02);
  EXPECT_DOUBLE_EQ(p.speed, 0.05);
  EXPECT_DOUBLE_EQ(p.duration, 7.0);
  EXPECT_DOUBLE_EQ(p.approach, 0.03);
  EXPECT_DOUBLE_EQ(p.hold, 0.2);
  EXPECT_DOUBLE_EQ(p.direction[1], 1.0);
  EXPECT_DOUBLE_EQ(p.orientation[1], 1.0);
  EXPECT_DOUBLE_EQ(p.rate_hz, 500.0);
}

TEST(MotionParamsYaml, UnknownKeyNamesLine) {
  const std::string e = ErrorOf("unknown.yaml", "script: slide\nsped: 0.1\n");
  EXPECT_NE(e.find("unknown.yaml:2: key 'sped': unknown"), std::string::npos) << e;
}

TEST(MotionParamsYaml, WrongTypesNameLineAndKey) {
  std::string e = ErrorOf("number.yaml", "speed: fast\n");
  EXPECT_NE(e.find("number.yaml:1: key 'speed': expected a number, got 'fast'"), std::string::npos)
      << e;
  e = ErrorOf("vector.yaml", "\n\ncentre: [1, 2]\n");
  EXPECT_NE(e.find("vector.yaml:3: key 'centre': expected a list of 3 numbers"), std::string::npos)
      << e;
}

TEST(MotionParamsYaml, SyntaxErrorAndMissingFile) {
  EXPECT_NE(ErrorOf("syntax.yaml", "centre: [1, 2\n").find("syntax.yaml:"), std::string::npos);
  MotionParams p;
  EXPECT_THROW(LoadMotionParamsYaml("/nonexistent/params.yaml", &p), InputError);
}

}  // namespace
}  // namespace probes
