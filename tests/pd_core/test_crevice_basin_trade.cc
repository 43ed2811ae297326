// A coherent answer pushed into its basin while another basin overtakes it:
// 17 poses of bench_pd's cow_armadillo haptic path (the report's first path,
// `haptic_work --seed 20240611`, poses 2255-2271, 1 ms apart, in W with the
// object's centre at the origin as bench_pd places it). The tool slides into
// a crevice; from pose 2266 the followed answer grows 5-8% per query while
// a basin about 60 degrees away stays near 2.5 mm. Scored against the
// independent reference PD at the last pose.
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
const std::vector<std::array<double, 7>> kCowIntoCrevice = {
    {0.017555471615779004, 0.029878580974084527, -0.036565796428539202, 0.60474440652644035, 0.11635084710231912, 0.55387716664084952, -0.56032737522582343},
    {0.017436943758831105, 0.030046851731261117, -0.036760205391619401, 0.60460214304979354, 0.11627461632173962, 0.55384283148607005, -0.56053062381133256},
    {0.017317400293463875, 0.030214845447377014, -0.036954230104583194, 0.60445983813436943, 0.11619837757182354, 0.55380845837150183, -0.56073383397867882},
    {0.017196847091685809, 0.030382560602978597, -0.037147869066465819, 0.60431749178992145, 0.11612213085779625, 0.5537740472995003, -0.56093700571393368},
    {0.017075289987614085, 0.03054999570508447, -0.037341120805866795, 0.60417510402620578, 0.11604587618488366, 0.55373959827242425, -0.56114013900317283},
    {0.016952734777765897, 0.030717149286784151, -0.037533983880486586, 0.60403267485298151, 0.11596961355831206, 0.55370511129263467, -0.56134323383247342},
    {0.016829187221347752, 0.030884019906843516, -0.037726456876671532, 0.60389020428001061, 0.11589334298330868, 0.55367058636249555, -0.56154629018791558},
    {0.016704653040542423, 0.031050606149317171, -0.037918538408966584, 0.60374769231705794, 0.11581706446510079, 0.5536360234843728, -0.56174930805558176},
    {0.016579137920793869, 0.03121690662316735, -0.038110227119676009, 0.60360513897389112, 0.1157407780089165, 0.55360142266063517, -0.56195228742155767},
    {0.016452647511089866, 0.031382919961889411, -0.038301521678431635, 0.60346254426028045, 0.11566448361998427, 0.55356678389365455, -0.56215522827193132},
    {0.016325187424242538, 0.031548644823143672, -0.038492420781768628, 0.60331990818599923, 0.11558818130353353, 0.55353210718580503, -0.56235813059279338},
    {0.016196763237166654, 0.031714079888393518, -0.038682923152708666, 0.60317723076082375, 0.11551187106479373, 0.55349739253946328, -0.56256099437023688},
    {0.016067380491155803, 0.031879223862549648, -0.038873027540350241, 0.60303451199453284, 0.11543555290899508, 0.5534626399570084, -0.56276381959035793},
    {0.01593704469215643, 0.032044075473620315, -0.039062732719466045, 0.60289175189690836, 0.1153592268413685, 0.55342784944082246, -0.56296660623925521},
    {0.015805761311039605, 0.032208633472367514, -0.039252037490107354, 0.60274895047773491, 0.1152828928671451, 0.55339302099328991, -0.56316935430302972},
    {0.01567353578387079, 0.032372896631968899, -0.039440940677215014, 0.6026061077467999, 0.11520655099155698, 0.55335815461679794, -0.56337206376778559},
    {0.015510610441471957, 0.032474548837718976, -0.039553542448815517, 0.6024632237138936, 0.11513020121983635, 0.5533232503137363, -0.56357473461962893},
};

// Before the check probed more directions per query while the answer grows
// fast (polydepth.cc, kCheckPerQueryFast), the check started at pose 2267
// found the other basin at 2272: at 2271 the answer was 2.96 mm against the
// reference's 2.48 (+19%, the bench's worst sampled pose on this path).
TEST(CreviceBasinTrade, CowIntoArmadilloCreviceFindsTheOtherBasinWhileGrowing) {
  for (const std::string f : {"cow.off", "armadillo.off"})
    PD_REQUIRE_FILE(std::string(PD_TEST_MESH_DIR) + "/" + f, "run scripts/fetch_meshes.sh");
  const auto tool = LoadScaled("cow.off", 0.047510300737962564);
  const auto object = LoadScaled("armadillo.off", 0.00080634978724717667);
  Isometry3 X_WS = Isometry3::Identity();
  X_WS.translation() = -object->center();
  PolyDepthSolver solver(tool, object);
  PenetrationResult r;
  Isometry3 X_WP;
  for (size_t i = 0; i < kCowIntoCrevice.size(); ++i) {
    X_WP = test::PoseOfRow(kCowIntoCrevice[i]);
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
