// Scenes with primitives and several objects: exact penalty answers for a
// sphere and a box on a plane, a stable hold of a box resting on a plane,
// wrenches of several touching objects summing, the cheap PD method chosen
// per pair, and the config errors of the new shape types.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "haptics/scene/build_scene.h"
#include "haptics/haptic_renderer.h"
#include "haptics/scene/load_scene_config.h"
#include "haptics/contact/penalty_wrench.h"
#include "haptics_test_util.h"

namespace haptics {
namespace {

namespace fs = std::filesystem;
constexpr double kK = 3000.0, kB = 5.0;

ObjectConfig Object(const std::string& name, ShapeVariant shape, const Vector3& p_WS,
                    const Quaternion& q_WS = Quaternion::Identity()) {
  ObjectConfig o;
  o.name = name;
  o.shape = {"objects[" + name + "].shape", std::move(shape)};
  o.X_WS.linear() = q_WS.toRotationMatrix();
  o.X_WS.translation() = p_WS;
  return o;
}

// The box_on_box test scene with another tool and these objects.
SceneConfig Scene(ShapeVariant tool, std::vector<ObjectConfig> objects) {
  SceneConfig c = test::BoxOnBoxConfig();
  c.tool.shape = {"tool.shape", std::move(tool)};
  c.objects = std::move(objects);
  c.contact.stiffness = kK;
  c.contact.damping = kB;
  return c;
}

using test::ToolAt;

TEST(ScenePrimitives, SphereOnAPlaneIsPushedOutByStiffnessTimesDepthAlongTheNormal) {
  const double r = 0.012, h = 0.03;  // plane at height h
  for (const Quaternion& q_WS :
       {Quaternion::Identity(), Quaternion(Eigen::AngleAxisd(0.4, Vector3(1, 2, 0).normalized()))}) {
    const SceneConfig config = Scene(SphereShape{r}, {Object("floor", PlaneShape{}, Vector3(0, 0, h), q_WS)});
    const SceneModels models = BuildSceneModels(config);
    PenaltyContact contact(models, config.contact);
    EXPECT_EQ(contact.solver(0).method(), pd::PdMethod::kClosedForm);
    const Vector3 n_W = q_WS * Vector3::UnitZ();
    for (double depth : {1e-4, 0.002, 0.005}) {
      // Centre on the plane's normal through (0.01, -0.02, h) rotated; the
      // sphere's lowest point `depth` below the plane.
      const Vector3 on_plane = Vector3(0, 0, h) + q_WS * Vector3(0.01, -0.02, 0);
      const ContactSummary& c = contact.Compute(ToolAt(on_plane + (r - depth) * n_W));
      ASSERT_EQ(c.num_in_contact, 1);
      // Exact up to the solver's separation margin (1e-8 of the pair's size).
      EXPECT_NEAR(c.max_depth, depth, 1e-7 * r);
      EXPECT_LT((c.wrench.w0.f_W - kK * depth * n_W).norm(), 1e-7 * kK * r) << c.wrench.w0.f_W.transpose();
      // A sphere's contact force passes through its centre, the tool origin.
      EXPECT_LT(c.wrench.w0.tau_W.norm(), 1e-9 * kK * r * r) << c.wrench.w0.tau_W.transpose();
      EXPECT_LT((c.wrench.K.topLeftCorner<3, 3>() - kK * n_W * n_W.transpose()).norm(), 1e-9 * kK);
    }
    // Just above the plane: no force.
    const ContactSummary& free = contact.Compute(ToolAt(Vector3(0, 0, h) + (r + 1e-4) * n_W));
    EXPECT_EQ(free.num_in_contact, 0);
    EXPECT_EQ(free.wrench.w0.f_W, Vector3::Zero());
  }
}

// A box resting flat on a plane: force k d straight up, acting at the centre
// of the bottom face whatever the box's position on the plane, so no torque
// about the box centre (the tool origin here).
TEST(ScenePrimitives, BoxRestingOnAPlaneHasNoTorqueAboutItsCentre) {
  const Vector3 half(0.02, 0.01, 0.008);
  const SceneConfig config = Scene(BoxShape{half}, {Object("floor", PlaneShape{}, Vector3::Zero())});
  const SceneModels models = BuildSceneModels(config);
  PenaltyContact contact(models, config.contact);
  for (const Vector3& xy : {Vector3(0, 0, 0), Vector3(0.3, -0.2, 0), Vector3(-0.05, 0.07, 0)}) {
    for (double depth : {0.0005, 0.003}) {
      const ContactSummary& c = contact.Compute(ToolAt(xy + Vector3(0, 0, half.z() - depth)));
      ASSERT_EQ(c.num_in_contact, 1);
      EXPECT_NEAR(c.wrench.w0.f_W.z(), kK * depth, 1e-7 * kK * half.norm());
      EXPECT_LT(c.wrench.w0.f_W.head<2>().norm(), 1e-9 * kK * depth);
      // Relative to the moment the force would have at the face's edge.
      EXPECT_LT(c.wrench.w0.tau_W.norm(), 2e-3 * kK * depth * half.x()) << c.wrench.w0.tau_W.transpose();
    }
  }
}

double Energy(const HapticRenderer& r, const SceneConfig& config) {
  const double d = r.contact().max_depth;
  return r.tool_dynamics().KineticEnergy() + r.coupling().PotentialEnergy(r.device(), r.tool()) +
         0.5 * config.contact.stiffness * d * d;
}

// The handle sinks 1 cm into the plane and holds: a passive system, so no
// energy gain while held, and it comes to rest without chatter.
TEST(ScenePrimitives, BoxHeldOnAPlaneIsStableAndGainsNoEnergy) {
  for (const Quaternion& q_WD : {Quaternion::Identity(), Quaternion(Eigen::AngleAxisd(0.25, Vector3::UnitX()))}) {
    SceneConfig config = Scene(BoxShape{Vector3(0.01, 0.01, 0.01)}, {Object("floor", PlaneShape{}, Vector3::Zero())});
    const SceneModels models = BuildSceneModels(config);
    HapticRenderer renderer(config, models);
    const Vector3 start(0.004, -0.002, 0.03), end(0.004, -0.002, 0.0);
    const int approach = 600, hold = 4000;
    double e_early = 0.0, e_last = 0.0, t = 0.0;
    Vector3 p_min = Vector3::Constant(1e9), p_max = -p_min, f_min = p_min, f_max = p_max;
    Vector3 tau_min = p_min, tau_max = p_max;
    for (int i = 0; i <= approach + hold; ++i, t += 1e-3) {
      const double a = std::min(1.0, static_cast<double>(i) / approach);
      const PoseSample pose = test::MakePose(i, start + a * (end - start), q_WD);
      const WrenchOutput& out = renderer.Tick(t, &pose);
      ASSERT_TRUE(out.wrench.AllFinite());
      const int into_hold = i - approach;
      const double e = Energy(renderer, config);
      if (into_hold >= 1000 && into_hold < 2000) e_early = std::max(e_early, e);
      if (into_hold >= hold - 1000) {
        e_last = std::max(e_last, e);
        const Vector3 p = renderer.tool().X_W.translation();
        p_min = p_min.cwiseMin(p), p_max = p_max.cwiseMax(p);
        f_min = f_min.cwiseMin(out.wrench.f_W), f_max = f_max.cwiseMax(out.wrench.f_W);
        tau_min = tau_min.cwiseMin(out.wrench.tau_W), tau_max = tau_max.cwiseMax(out.wrench.tau_W);
      }
    }
    EXPECT_GT(e_early, 0.0);
    EXPECT_LE(e_last, e_early * (1.0 + 1e-6) + 1e-12);
    EXPECT_LT((p_max - p_min).maxCoeff(), 1e-6);
    EXPECT_LT((f_max - f_min).maxCoeff(), 1e-4);
    EXPECT_LT((tau_max - tau_min).maxCoeff(), 1e-5);
    EXPECT_GT(renderer.output().wrench.f_W.z(), 5.0);  // 750 N/m in series, 1 cm: 7.5 N
    EXPECT_EQ(renderer.counts().pd_invalid, 0);
  }
}

// A box tool in the corner of a floor and a wall (and above a ball it also
// presses): the summed wrench, stiffness and damping equal the sum of each
// object's alone.
TEST(ScenePrimitives, WrenchOfTouchingObjectsIsTheSumOfEachAlone) {
  const ShapeVariant tool = BoxShape{Vector3(0.01, 0.01, 0.01)};
  const std::vector<ObjectConfig> objects = {
      Object("floor", PlaneShape{}, Vector3::Zero()),
      // A wall: the half-space x >= 0.02 (its +z turned to -x).
      Object("wall", PlaneShape{}, Vector3(0.02, 0, 0), Quaternion(Eigen::AngleAxisd(-M_PI / 2, Vector3::UnitY()))),
      Object("block", BoxShape{Vector3(0.01, 0.03, 0.02)}, Vector3(-0.007, 0, 0.02)),  // x <= 0.003
      Object("far_ball", SphereShape{0.01}, Vector3(0.5, 0.5, 0.5)),
  };
  RigidState state = ToolAt(Vector3(0.0115, 0.002, 0.0085),
                            Eigen::AngleAxisd(0.05, Vector3(1, 1, 0).normalized()).toRotationMatrix());
  state.v_W = Vector3(0.01, 0.0, -0.02);
  state.w_W = Vector3(0.0, 0.3, 0.1);
  const SceneConfig all = Scene(tool, objects);
  PenaltyContact together(BuildSceneModels(all), all.contact);
  const ContactSummary sum = together.Compute(state);
  EXPECT_EQ(sum.num_in_contact, 3);
  EXPECT_EQ(sum.num_culled, 1);  // the far ball
  LinearizedWrench expected;
  double max_depth = 0.0;
  for (int i = 0; i < 3; ++i) {
    const SceneConfig one = Scene(tool, {objects[i]});
    PenaltyContact alone(BuildSceneModels(one), one.contact);
    const ContactSummary& c = alone.Compute(state);
    ASSERT_EQ(c.num_in_contact, 1) << objects[i].name;
    EXPECT_GT(c.wrench.w0.f_W.norm(), 0.1) << objects[i].name;
    expected += c.wrench;
    max_depth = std::max(max_depth, c.max_depth);
  }
  const double f_scale = expected.w0.f_W.norm();
  EXPECT_LT((sum.wrench.w0.f_W - expected.w0.f_W).norm(), 1e-9 * f_scale);
  EXPECT_LT((sum.wrench.w0.tau_W - expected.w0.tau_W).norm(), 1e-9 * f_scale * 0.02);
  EXPECT_LT((sum.wrench.K - expected.K).norm(), 1e-9 * expected.K.norm());
  EXPECT_LT((sum.wrench.D - expected.D).norm(), 1e-9 * expected.D.norm());
  EXPECT_EQ(sum.max_depth, max_depth);
}

TEST(ScenePrimitives, EachPairUsesTheCheapestMethodForItsKinds) {
  const SceneConfig spoon = LoadSceneConfig(test::ConfigDir() + "/spoon_in_cup.yaml");
  SceneConfig config = Scene(BoxShape{Vector3(0.01, 0.01, 0.01)},
                             {Object("floor", PlaneShape{}, Vector3::Zero()),
                              Object("can", CylinderShape{0.01, 0.02}, Vector3(0.1, 0, 0)),
                              Object("cup", spoon.objects[0].shape.shape, Vector3(-0.1, 0, 0))});
  PenaltyContact box_tool(BuildSceneModels(config), config.contact);
  EXPECT_EQ(box_tool.solver(0).method(), pd::PdMethod::kClosedForm);    // box-plane
  EXPECT_EQ(box_tool.solver(1).method(), pd::PdMethod::kConvexGjkEpa);  // box-cylinder
  EXPECT_EQ(box_tool.solver(2).method(), pd::PdMethod::kPolyDepth);     // box-cup (non-convex)
  config.tool.shape = spoon.tool.shape;
  PenaltyContact spoon_tool(BuildSceneModels(config), config.contact);
  EXPECT_EQ(spoon_tool.solver(0).method(), pd::PdMethod::kClosedForm);  // mesh-plane
  EXPECT_EQ(spoon_tool.solver(2).method(), pd::PdMethod::kPolyDepth);
  // Shipped scenes: box on box is now a convex pair.
  const SceneConfig box_on_box = LoadSceneConfig(test::ConfigDir() + "/box_on_box.yaml");
  PenaltyContact shipped(BuildSceneModels(box_on_box), box_on_box.contact);
  EXPECT_EQ(shipped.solver(0).method(), pd::PdMethod::kConvexGjkEpa);
}

// Config errors of the new shape types name the file, the key and the value.
class ShapeConfigTest : public ::testing::Test {
 protected:
  void SetUp() override {
    scene_ = test::ConfigDir() + "/primitives_only.yaml";
    fs::create_directories(dir_ / "devices");
    fs::copy_file(test::ConfigDir() + "/devices/sigma7.yaml", dir_ / "devices/sigma7.yaml");
    std::ifstream in(scene_);
    text_.assign((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  }
  // primitives_only.yaml with `from` replaced by `to`, written into dir_.
  std::string Write(const std::string& from, const std::string& to) {
    const fs::path path = dir_ / "scene.yaml";
    test::WriteFile(path, test::Edited(text_, from, to));
    return path.string();
  }
  static void ExpectError(const std::string& path, const std::string& key,
                          std::initializer_list<std::string> parts) {
    test::ExpectConfigError(path, path + ": " + key, parts);
  }

  pd::test::ScopedTempDir tmp_{"haptics_test_shapes"};
  const fs::path dir_ = tmp_.path();
  std::string scene_, text_;
};

constexpr const char* kToolShape = "shape: {type: capsule, radius: 0.008, length: 0.02}";
constexpr const char* kBallShape = "shape: {type: sphere, radius: 0.02}";

TEST_F(ShapeConfigTest, PlaneAsTheToolIsRefused) {
  ExpectError(Write(kToolShape, "shape: {type: plane}"), "tool.shape.type", {"plane", "cannot be the tool"});
}

TEST_F(ShapeConfigTest, BadSizesAreNamed) {
  ExpectError(Write(kBallShape, "shape: {type: sphere, radius: -0.02}"), "objects[2].shape.radius",
              {"-0.02", "(0, 10] m"});
  ExpectError(Write(kBallShape, "shape: {type: sphere}"), "objects[2].shape.radius", {"missing"});
  ExpectError(Write(kToolShape, "shape: {type: capsule, radius: 0.008, length: -1}"), "tool.shape.length",
              {"[0, 10] m"});
  ExpectError(Write(kBallShape, "shape: {type: cylinder, radius: 0.01, length: 0}"), "objects[2].shape.length",
              {"(0, 10] m"});
  ExpectError(Write(kBallShape, "shape: {type: mesh, file: ../../x.obj, convex: maybe}"),
              "objects[2].shape.file", {"does not exist"});
  ExpectError(Write(kBallShape, "shape: {type: cone, radius: 0.02}"), "objects[2].shape.type", {"cone", "plane"});
}

TEST_F(ShapeConfigTest, MeshDeclaredConvexIsCheckedAtLoad) {
  // An L-shaped prism (10 mm units): closed but not convex.
  test::WriteFile(dir_ / "ell.obj",
                  "v 0 0 0\nv 2 0 0\nv 2 1 0\nv 1 1 0\nv 1 2 0\nv 0 2 0\n"
                  "v 0 0 1\nv 2 0 1\nv 2 1 1\nv 1 1 1\nv 1 2 1\nv 0 2 1\n"
                  "f 6 5 4 3 2 1\nf 7 8 9 10 11 12\n"
                  "f 1 2 8 7\nf 2 3 9 8\nf 3 4 10 9\nf 4 5 11 10\nf 5 6 12 11\nf 6 1 7 12\n");
  const std::string path = Write(kBallShape, "shape: {type: mesh, file: ell.obj, scale: 0.01, convex: true}");
  ExpectError(path, "objects[2].shape.convex", {(dir_ / "ell.obj").string(), "not convex"});
  // Declared general, it loads as a (non-convex) mesh.
  const SceneModels models =
      BuildSceneModels(LoadSceneConfig(Write(kBallShape, "shape: {type: mesh, file: ell.obj, scale: 0.01}")));
  EXPECT_EQ(models.objects[2].geometry->kind(), pd::ShapeKind::kMesh);
  // A convex one loads as a convex mesh.
  const SceneModels prism = BuildSceneModels(LoadSceneConfig(test::ConfigDir() + "/table_objects.yaml"));
  EXPECT_EQ(prism.objects[1].geometry->kind(), pd::ShapeKind::kConvexMesh);
  // convex must be true or false.
  ExpectError(Write(kBallShape, "shape: {type: mesh, file: ell.obj, convex: maybe}"), "objects[2].shape.convex",
              {"maybe"});
}

TEST_F(ShapeConfigTest, CylinderSegmentsAreAcceptedWithAWarning) {
  const SceneConfig c = LoadSceneConfig(
      Write(kBallShape, "shape: {type: cylinder, radius: 0.01, length: 0.02, segments: 24}"));
  ASSERT_EQ(c.warnings.size(), 1u);
  EXPECT_NE(c.warnings[0].find("objects[2].shape.segments"), std::string::npos) << c.warnings[0];
  EXPECT_NE(c.warnings[0].find("ignored"), std::string::npos) << c.warnings[0];
  const SceneModels m = BuildSceneModels(c);
  EXPECT_EQ(m.objects[2].geometry->kind(), pd::ShapeKind::kCylinder);
}

TEST_F(ShapeConfigTest, CacheDirIsResolvedAgainstTheConfigFile) {
  const SceneConfig c = LoadSceneConfig(Write("name: primitives_only\n", "name: primitives_only\ncache_dir: cache\n"));
  EXPECT_EQ(c.cache_dir, (dir_ / "cache").string());
  EXPECT_TRUE(LoadSceneConfig(scene_).cache_dir.empty());
}

}  // namespace
}  // namespace haptics
