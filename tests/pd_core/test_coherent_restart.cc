// A coherent restart whose near step-offs all collide: 20 poses of bench_pd's
// cow_armadillo haptic path (the report's first path, `haptic_work --seed
// 20240611`, poses 2708-2727, 1 ms apart, in W with the object's centre at
// the origin as bench_pd places it). At the last pose the previous answer's
// prediction and its step-offs of 1 and 4 motions collide (a feature leans
// over the answer's direction). Scored against the independent reference PD
// at the last pose.
#include <gtest/gtest.h>

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "pd_core/polydepth/polydepth.h"
#include "pd_core/reference/reference_pd.h"
#include "tests/pd_core/pair_pd_test_helpers.h"
#include "tests/pd_core/scaled_mesh_model.h"
#include "tests/prerequisites.h"

namespace pd {
namespace {

using test::LoadScaled;

// x y z (m), qw qx qy qz of the tool in W, one row per millisecond.
const std::vector<std::array<double, 7>> kCowUnderOverhang = {
    {0.010058602016221488, 0.034830219751384693, -0.042074100104868534, 0.53621155603546777, 0.081083729797571683, 0.53447783075967892, -0.64825615644015644},
    {0.010218181537396284, 0.034676254492558213, -0.041898928792210258, 0.53605156184357883, 0.081004431640926647, 0.53442658074512017, -0.64844061786155061},
    {0.010376918105273001, 0.034521942265017209, -0.041723298980298848, 0.53589153091129527, 0.08092512793232548, 0.53437529410154117, -0.64862503483952583},
    {0.010534806587791804, 0.0343672838383881, -0.041547211315023209, 0.53573146324958532, 0.080845818677203557, 0.53432397083245753, -0.64880940736144221},
    {0.010691841819227993, 0.034212279999858868, -0.041370666461433087, 0.53557135886942009, 0.080766503880996515, 0.53427261094138612, -0.64899373541466343},
    {0.010848018599919233, 0.03405693155444843, -0.041193665104045755, 0.53541121778177281, 0.080687183549140659, 0.53422121443184767, -0.64917801898655525},
    {0.011003331695990166, 0.033901239325280413, -0.041016207947158018, 0.53525103999761947, 0.080607857687072529, 0.53416978130736426, -0.64936225806448733},
    {0.01115777583907464, 0.033745204153861758, -0.040838295715163703, 0.53509082552793852, 0.080528526300228914, 0.53411831157146183, -0.64954645263583211},
    {0.011311345726035368, 0.033588826900365833, -0.040659929152876563, 0.53493057438371061, 0.080449189394047119, 0.53406680522766747, -0.64973060268796534},
    {0.01146403601868104, 0.033432108443920597, -0.040481109025858851, 0.53477028657591941, 0.080369846973964765, 0.53401526227951168, -0.64991470820826536},
    {0.011615841343480843, 0.033275049682901535, -0.040301836120755649, 0.53460996211555079, 0.080290499045419961, 0.53396368273052708, -0.65009876918411369},
    {0.01176675629127651, 0.033117651535229671, -0.040122111245634987, 0.53444960101359329, 0.080211145613851328, 0.53391206658424883, -0.65028278560289521},
    {0.011916775416991572, 0.03295991493867468, -0.039941935230333972, 0.53428920328103779, 0.080131786684697379, 0.53386041384421445, -0.65046675745199756},
    {0.012066539069023118, 0.0328035965771689, -0.039763437159931157, 0.53412876892887784, 0.080052422263397358, 0.53380872451396466, -0.65065068471881138},
    {0.012304997266436904, 0.03288638085289005, -0.039874810774402615, 0.53396829796810952, 0.079973052355391039, 0.53375699859704184, -0.65083456739073065},
    {0.012546403779296573, 0.032974957437996263, -0.039993248974698331, 0.53380779040973125, 0.079893676966117905, 0.53370523609699105, -0.65101840545515199},
    {0.012788361715452242, 0.033062936089243107, -0.040111003265147278, 0.5336472462647438, 0.079814296101018631, 0.53365343701736068, -0.65120219889947595},
    {0.013026084138244721, 0.033138153795643013, -0.040213313461739689, 0.53348666554415125, 0.079734909765533865, 0.53360160136170043, -0.65138594771110458},
    {0.013264457981985589, 0.033213243987433916, -0.04031550610362044, 0.53332604825895913, 0.07965551796510438, 0.53354972913356324, -0.65156965187744487},
    {0.013491044884082447, 0.033257542994455595, -0.040380350270979803, 0.5331653944201763, 0.079576120705171949, 0.53349782033650417, -0.6517533113859052},
};

// Before the clearing direction was tried ahead of the far step-offs
// (polydepth.cc, step 1), the restart at the last pose stepped off 64
// motions along the previous answer, landed at 7x the answer's length and
// iterated back down into a deeper basin: 2.13 mm in 19k box and triangle
// tests, against 1.94 mm in 3.9k from the clearing direction (the
// reference: 1.86 mm).
TEST(CoherentRestart, CowUnderArmadilloOverhangStepsOffAlongTheClearingDirection) {
  for (const std::string f : {"cow.off", "armadillo.off"})
    PD_REQUIRE_FILE(std::string(PD_TEST_MESH_DIR) + "/" + f, "run scripts/fetch_meshes.sh");
  const auto tool = LoadScaled("cow.off", 0.047510300737962564);
  const auto object = LoadScaled("armadillo.off", 0.00080634978724717667);
  Isometry3 X_WS = Isometry3::Identity();
  X_WS.translation() = -object->center();
  PolyDepthSolver solver(tool, object);
  PenetrationResult r;
  Isometry3 X_WP;
  for (size_t i = 0; i < kCowUnderOverhang.size(); ++i) {
    X_WP = test::PoseOfRow(kCowUnderOverhang[i]);
    r = solver.Solve(X_WP, X_WS, /*coherent=*/true);
    ASSERT_TRUE(r.in_collision) << "pose " << i;
    ASSERT_TRUE(r.valid) << "pose " << i;
    EXPECT_FALSE(i > 0 && r.warm_start_failed) << "pose " << i;
  }
  EXPECT_FALSE(ReferenceInCollision(tool->mesh(), X_WP, true, object->mesh(), X_WS, true,
                                    r.translation_W));
  const ReferencePdResult ref = ReferencePenetrationDepth(
      tool->mesh(), X_WP, true, object->mesh(), X_WS, true, test::BenchHapticReferenceOptions());
  ASSERT_TRUE(ref.in_collision);
  RecordProperty("depth_um", static_cast<int>(r.depth * 1e6));
  RecordProperty("reference_um", static_cast<int>(ref.depth * 1e6));
  EXPECT_LE(r.depth, 1.05 * ref.depth) << "reference " << ref.depth;
}

}  // namespace
}  // namespace pd
