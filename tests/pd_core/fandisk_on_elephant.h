#pragma once
// bench_pd's fandisk_elephant haptic pair as a test fixture: the CGAL
// fandisk as the tool and the refined elephant as the object, scaled as the
// bench scales them, and pose 1200 of the bench's path (the tool 2 mm deep
// in the object; object at the world origin).
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "pd_core/mesh/collision_model.h"
#include "tests/pd_core/scaled_mesh_model.h"
#include "tests/prerequisites.h"

namespace pd {
namespace test {

class FandiskOnElephant : public ::testing::Test {
 protected:
  void SetUp() override {
    for (const char* f : {"fandisk.off", "refined_elephant.off"})
      PD_REQUIRE_FILE(std::string(PD_TEST_MESH_DIR) + "/" + f, "run scripts/fetch_meshes.sh");
    tool = LoadScaled("fandisk.off", 0.034431803204303821);
    object = LoadScaled("refined_elephant.off", 0.12763984046501484);
  }
  // Pose 1200 of the path: the tool's orientation and position in W.
  static Quaternion Pose1200Rotation() {
    return Quaternion(0.74771591051074504, 0.20407979086249584, 0.56654559954783568,
                      -0.27981858366375667)
        .normalized();
  }
  static Vector3 Pose1200Position() {
    return Vector3(-0.021064379799368926, 0.012639199578282974, -0.01414136732652058);
  }
  std::shared_ptr<const CollisionModel> tool, object;
};

}  // namespace test
}  // namespace pd
