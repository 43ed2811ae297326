// Penalty force and torque against analytic answers: a box pressed into a
// box by a known depth, and a cube standing on one corner off the tool's axis.
#include "haptics/contact/penalty_wrench.h"

#include <gtest/gtest.h>

#include <functional>

#include "haptics/io/wrench_output.h"
#include "haptics_test_util.h"

namespace haptics {
namespace {

constexpr double kK = 3000.0, kB = 5.0;

struct Fixture {
  SceneConfig config = test::BoxOnBoxConfig();
  SceneModels models;
  std::unique_ptr<PenaltyContact> contact;
  explicit Fixture(const pd::PolyDepthOptions& options = {},
                   const std::function<void(SceneConfig&)>& edit = nullptr) {
    if (edit) edit(config);
    config.contact.stiffness = kK;
    config.contact.damping = kB;
    models = BuildSceneModels(config);
    contact = std::make_unique<PenaltyContact>(models, config.contact, options);
  }
};

using test::ToolAt;

TEST(PenaltyContact, BoxPressedIntoBoxPushesStraightOutByStiffnessTimesDepth) {
  Fixture f;
  for (double depth : {0.0005, 0.002, 0.004}) {
    // Tool box (half size 1 cm) centred 1 cm - depth above the table top z = 0.
    const RigidState tool = ToolAt(Vector3(0.005, -0.003, 0.01 - depth));
    const ContactSummary& c = f.contact->Compute(tool);
    const pd::PenetrationResult& r = f.contact->last_result(0);
    ASSERT_TRUE(r.in_collision);
    ASSERT_TRUE(r.valid);
    EXPECT_EQ(c.num_in_contact, 1);
    EXPECT_EQ(c.num_invalid, 0);
    EXPECT_NEAR(c.max_depth, depth, 1e-7);
    EXPECT_NEAR(c.wrench.w0.f_W.z(), kK * depth, kK * 1e-7) << depth;
    EXPECT_NEAR(c.wrench.w0.f_W.head<2>().norm(), 0.0, 1e-6 * kK * depth) << depth;
    // Stiffness for the implicit step: k n n^T along z only.
    EXPECT_NEAR(c.wrench.K(2, 2), kK, 1e-6 * kK);
    EXPECT_NEAR((c.wrench.K.topLeftCorner<2, 2>().norm()), 0.0, 1e-6 * kK);
    EXPECT_GT(c.num_regions, 0);
  }
}

TEST(PenaltyContact, DampingAddsWhileEnteringAndNeverPulls) {
  Fixture f;
  const double depth = 0.002;
  RigidState tool = ToolAt(Vector3(0, 0, 0.01 - depth));
  tool.v_W = Vector3(0, 0, -0.1);  // pressing in
  EXPECT_NEAR(f.contact->Compute(tool).wrench.w0.f_W.z(), kK * depth + kB * 0.1, 1e-3);
  tool.v_W = Vector3(0, 0, 0.5);  // leaving slowly: less force
  EXPECT_NEAR(f.contact->Compute(tool).wrench.w0.f_W.z(), kK * depth - kB * 0.5, 1e-3);
  tool.v_W = Vector3(0, 0, 5.0);  // leaving fast: damping would pull; it must not
  const ContactSummary& c = f.contact->Compute(tool);
  EXPECT_EQ(c.wrench.w0.f_W, Vector3::Zero());
  EXPECT_EQ(c.wrench.w0.tau_W, Vector3::Zero());
  EXPECT_EQ(c.wrench.K.norm(), 0.0);
}

// A cube balanced on one corner, its tool origin 3 cm to the side of that
// corner: one vertex-face contact of local depth d, so the torque about the
// tool origin is r x (k d z) = (0, -0.03 k d, 0) exactly.
TEST(PenaltyContact, OffCentreContactTurnsTheToolWithTheRightSignAndMagnitude) {
 for (TorqueModel model : {TorqueModel::kPressureCentre, TorqueModel::kRegionPoints}) {
  SCOPED_TRACE(model == TorqueModel::kPressureCentre ? "pressure_centre" : "region_points");
  const double h = 0.01;
  SceneConfig config = test::BoxOnBoxConfig();
  config.contact.stiffness = kK;
  config.contact.damping = kB;
  config.contact.torque_model = model;
  config.tool.X_TG.linear() =
      Quaternion::FromTwoVectors(Vector3(1, 1, 1), Vector3(0, 0, -1)).toRotationMatrix();
  config.tool.X_TG.translation() = Vector3(0.03, 0, 0);
  const SceneModels models = BuildSceneModels(config);
  PenaltyContact contact(models, config.contact);
  const double corner = std::sqrt(3.0) * h;  // corner below the cube centre
  for (double depth : {0.001, 0.003}) {
    const Vector3 p_WT(-0.01, 0.005, corner - depth);
    const ContactSummary& c = contact.Compute(ToolAt(p_WT));
    ASSERT_TRUE(contact.last_result(0).valid);
    EXPECT_NEAR(c.max_depth, depth, 1e-7);
    EXPECT_TRUE(c.wrench.w0.f_W.isApprox(Vector3(0, 0, kK * depth), 1e-5)) << c.wrench.w0.f_W.transpose();
    const Vector3 expected(0, -0.03 * kK * depth, 0);
    EXPECT_LT((c.wrench.w0.tau_W - expected).norm(), 1e-4 * expected.norm())
        << "torque " << c.wrench.w0.tau_W.transpose() << " expected " << expected.transpose();
    EXPECT_LT(c.wrench.w0.tau_W.y(), 0.0);
    // Rotational stiffness for the implicit step: k (r x n)(r x n)^T.
    EXPECT_NEAR(c.wrench.K(4, 4), kK * 0.03 * 0.03, 1e-3 * kK * 0.03 * 0.03);
  }
  // Mirrored: the corner on the other side turns the other way.
  config.tool.X_TG.translation() = Vector3(-0.03, 0, 0);
  const SceneModels mirrored = BuildSceneModels(config);
  PenaltyContact contact2(mirrored, config.contact);
  const ContactSummary& c = contact2.Compute(ToolAt(Vector3(0.01, 0.005, corner - 0.002)));
  EXPECT_NEAR(c.wrench.w0.tau_W.y(), 0.03 * kK * 0.002, 1e-4 * 0.03 * kK * 0.002);
 }
}

// A flat face pressed down 3 cm to the side of the tool origin: the force
// k d acts at the face centre whatever regions PolyDepth reports, so the
// torque is (0.03, 0, -h) x (0, 0, k d) = (0, -0.03 k d, 0).
TEST(PenaltyContact, FlatFaceOffCentreActsAtTheFaceCentre) {
  SceneConfig config = test::BoxOnBoxConfig();
  config.contact.stiffness = kK;
  config.contact.damping = kB;
  config.tool.X_TG.translation() = Vector3(0.03, 0, 0);
  const SceneModels models = BuildSceneModels(config);
  PenaltyContact contact(models, config.contact);
  for (double depth : {0.001, 0.004}) {
    const ContactSummary& c = contact.Compute(ToolAt(Vector3(-0.02, 0.004, 0.01 - depth)));
    ASSERT_TRUE(contact.last_result(0).valid);
    EXPECT_NEAR(c.wrench.w0.f_W.z(), kK * depth, 1e-6 * kK);
    const Vector3 expected(0, -0.03 * kK * depth, 0);
    EXPECT_LT((c.wrench.w0.tau_W - expected).norm(), 1e-3 * expected.norm())
        << c.wrench.w0.tau_W.transpose() << " regions " << c.num_regions;
  }
}

// Tilting a flat, centred press by +-1 mrad: the pressure-centre torque
// restores smoothly (small, opposite signs); the plain region-point torque
// jumps between opposite corners (bang-bang), which is why it chatters.
TEST(PenaltyContact, FlatFaceTorqueIsContinuousInTilt) {
  const double depth = 0.002, tilt = 1e-3;
  auto torque_at = [&](TorqueModel model, double angle) {
    SceneConfig config = test::BoxOnBoxConfig();
    config.contact.stiffness = kK;
    config.contact.torque_model = model;
    const SceneModels models = BuildSceneModels(config);
    PenaltyContact contact(models, config.contact);
    const Matrix3 R = Eigen::AngleAxisd(angle, Vector3::UnitX()).toRotationMatrix();
    return Vector3(contact.Compute(ToolAt(Vector3(0.003, -0.002, 0.01 - depth), R)).wrench.w0.tau_W);
  };
  const double tau_jump_scale = kK * depth * 0.01;  // force times half the box width
  const Vector3 plus = torque_at(TorqueModel::kPressureCentre, tilt);
  const Vector3 minus = torque_at(TorqueModel::kPressureCentre, -tilt);
  EXPECT_LT(plus.x(), 0.0);  // restoring
  EXPECT_GT(minus.x(), 0.0);
  EXPECT_LT((plus - minus).norm(), 0.05 * tau_jump_scale);
  const Vector3 plus_rp = torque_at(TorqueModel::kRegionPoints, tilt);
  const Vector3 minus_rp = torque_at(TorqueModel::kRegionPoints, -tilt);
  EXPECT_GT((plus_rp - minus_rp).norm(), 0.5 * tau_jump_scale);
}

TEST(PenaltyContact, FarObjectsAreNotQueried) {
  Fixture f;
  const int64_t before = f.contact->query_count();
  const ContactSummary& far = f.contact->Compute(ToolAt(Vector3(0.0, 0.0, 0.5)));
  EXPECT_EQ(far.num_candidates, 0);
  EXPECT_EQ(far.num_culled, 1);
  EXPECT_EQ(f.contact->query_count(), before);
  EXPECT_FALSE(f.contact->last_result(0).in_collision);
  // Close but not touching: queried, no force.
  const ContactSummary& near = f.contact->Compute(ToolAt(Vector3(0.0, 0.0, 0.0105)));
  EXPECT_EQ(near.num_candidates, 1);
  EXPECT_EQ(near.num_in_contact, 0);
  EXPECT_EQ(near.wrench.w0.f_W, Vector3::Zero());
}

TEST(PenaltyContact, UnverifiedPdIsDroppedAndCounted) {
  // A solver with no way to find a start cannot verify anything.
  pd::PolyDepthOptions crippled;
  crippled.num_maximally_clear = 0;
  crippled.use_centroid = false;
  crippled.num_random = 0;
  crippled.num_sampling_directions = 0;
  // Box meshes (thin plates), so that the pair is solved by PolyDepth.
  Fixture f(crippled, [](SceneConfig& c) {
    c.tool.shape.shape = ThinPlateShape{0.01, 0.01, 0.01};
    c.objects[0].shape.shape = ThinPlateShape{0.05, 0.05, 0.01};
  });
  ASSERT_EQ(f.contact->solver(0).method(), pd::PdMethod::kPolyDepth);
  const ContactSummary& c = f.contact->Compute(ToolAt(Vector3(0, 0, 0.008)));
  EXPECT_TRUE(f.contact->last_result(0).in_collision);
  EXPECT_FALSE(f.contact->last_result(0).valid);
  EXPECT_EQ(c.num_invalid, 1);
  EXPECT_EQ(c.num_in_contact, 0);
  EXPECT_EQ(c.wrench.w0.f_W, Vector3::Zero());
  EXPECT_EQ(c.wrench.w0.tau_W, Vector3::Zero());
  EXPECT_EQ(f.contact->invalid_count(), 1);
}

// Issue 12, item 3: an answer that is not valid used to drop the object's
// force for the tick: the wall let go exactly when the solver struggled. The
// pair's last valid contact is held instead, at the current pose, fading
// over contact.invalid_hold_ms, and counted. A solver whose only start is the
// centroid difference, without warm start, verifies the tool 2 mm in the
// table and cannot answer at all with the tool's centroid on the table's.
TEST(PenaltyContact, UnverifiedPdHoldsTheLastValidContactOfThePair) {
  pd::PolyDepthOptions centroid_only;
  centroid_only.num_maximally_clear = 0;
  centroid_only.use_centroid = true;
  centroid_only.num_random = 0;
  centroid_only.num_sampling_directions = 0;
  centroid_only.warm_start = false;
  Fixture f(centroid_only, [](SceneConfig& c) {
    c.tool.shape.shape = ThinPlateShape{0.01, 0.01, 0.01};
    c.objects[0].shape.shape = ThinPlateShape{0.05, 0.05, 0.01};
    c.contact.invalid_hold_s = 0.1;  // 100 calls at 1 kHz
  });
  ASSERT_EQ(f.contact->solver(0).method(), pd::PdMethod::kPolyDepth);
  const ContactSummary& valid = f.contact->Compute(ToolAt(Vector3(0, 0, 0.008)));
  ASSERT_TRUE(f.contact->last_result(0).valid);
  EXPECT_NEAR(valid.wrench.w0.f_W.z(), kK * 0.002, 1e-4);

  // Centroid on the table's (0, 0, -0.01): 18 mm deeper than the valid answer.
  const ContactSummary& held = f.contact->Compute(ToolAt(Vector3(0, 0, -0.01)));
  ASSERT_TRUE(f.contact->last_result(0).in_collision);
  ASSERT_FALSE(f.contact->last_result(0).valid);
  EXPECT_EQ(held.num_invalid, 1);
  EXPECT_EQ(held.num_held, 1);
  EXPECT_EQ(held.num_in_contact, 1);
  // The held plane, evaluated where the tool is now: 20 mm deep.
  EXPECT_NEAR(held.wrench.w0.f_W.z(), kK * 0.020, 1e-4);
  EXPECT_NEAR(held.wrench.K(2, 2), kK, 1e-4);
  EXPECT_TRUE(f.contact->last_flags() & kFlagPdInvalid);
  EXPECT_TRUE(f.contact->last_flags() & kFlagContactHeld);
  EXPECT_EQ(f.contact->invalid_count(), 1);
  // Still unverified: the held contact fades over 100 calls.
  for (int i = 0; i < 49; ++i) f.contact->Compute(ToolAt(Vector3(0, 0, -0.01)));
  EXPECT_NEAR(f.contact->Compute(ToolAt(Vector3(0, 0, -0.01))).wrench.w0.f_W.z(), kK * 0.020 * 0.5, 1e-4);
  EXPECT_EQ(f.contact->local().counts().held_ticks, 51);
  for (int i = 0; i < 50; ++i) f.contact->Compute(ToolAt(Vector3(0, 0, -0.01)));
  EXPECT_EQ(f.contact->Compute(ToolAt(Vector3(0, 0, -0.01))).wrench.w0.f_W.norm(), 0.0);
  // A verified answer again: the fresh contact, no flag.
  const ContactSummary& back = f.contact->Compute(ToolAt(Vector3(0, 0, 0.005)));
  EXPECT_NEAR(back.wrench.w0.f_W.z(), kK * 0.005, 1e-4);
  EXPECT_EQ(f.contact->last_flags() & (kFlagPdInvalid | kFlagContactHeld), 0);
}

}  // namespace
}  // namespace haptics
