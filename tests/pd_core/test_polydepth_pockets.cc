// Warm PolyDepth along stretches of the benchmark's haptic paths (a mesh tool
// sliding over a mesh object, one pose per millisecond) where the solver used
// to answer from inside thin pockets of free space: the answer was free but
// collided again 2e-6 of the pair's size further along itself (the tool
// wedged against a feature leaning over it), and the next pose's step-off
// along that answer landed in the feature and restarted cold (6-11 ms).
// Every answer here must be free a further 2e-6 x size along itself, checked
// by the independent reference collision test, and no pose after the first
// may restart cold.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "pd_core/mesh/load_mesh.h"
#include "pd_core/polydepth/polydepth.h"
#include "pd_core/proximity/model_pair.h"
#include "pd_core/reference/reference_pd.h"
#include "tests/prerequisites.h"

namespace pd {
namespace {

// Poses X_SP of the tool in the object's file frame (scaled), x y z qw qx qy
// qz, 1 ms apart: bench_pd's haptic paths fandisk_elephant (poses 1200-1216)
// and cow_armadillo (480-492).
const std::vector<std::array<double, 7>> kFandiskOverElephant = {
    {-0.021064379799368926, 0.012639199578282974, -0.01414136732652058, 0.74771591051074504, 0.20407979086249584, 0.56654559954783568, -0.27981858366375667},
    {-0.021146250743697421, 0.012559124024249491, -0.014041524120126095, 0.74764627027083186, 0.20402785239640014, 0.56655751054777204, -0.28001835161027938},
    {-0.021226552706625452, 0.012478223797737841, -0.013940780514537206, 0.74757659444559432, 0.20397590421929859, 0.56656939458156985, -0.28021810622891652},
    {-0.021302657209698383, 0.012394966958450297, -0.013837448731494421, 0.74750688303834845, 0.20392394633366367, 0.56658125164866358, -0.28041784751016041},
    {-0.021372902781230649, 0.012308431755045163, -0.013730517491158034, 0.74743713605241235, 0.20387197874196847, 0.56659308174848888, -0.28061757544450416},
    {-0.021439984909101966, 0.01222023685027508, -0.013621774451252251, 0.74736735349110595, 0.20382000144668641, 0.56660488488048244, -0.28081729002244155},
    {-0.021494713796538435, 0.012125172025609188, -0.013505492640257482, 0.74729753535775045, 0.20376801445029133, 0.56661666104408281, -0.28101699123446672},
    {-0.021549116165088311, 0.012030167872829452, -0.013389300497693192, 0.74722768165566888, 0.20371601775525791, 0.56662841023872956, -0.28121667907107462},
    {-0.02159729266091397, 0.011931926233123141, -0.013269577100286339, 0.74715779238818625, 0.2036640113640607, 0.56664013246386302, -0.2814163535227609},
    {-0.021635512339441346, 0.011828450487170213, -0.013144138896587934, 0.74708786755862888, 0.20361199527917512, 0.56665182771892542, -0.28161601458002161},
    {-0.021667902956087295, 0.011722108864120711, -0.013015591613185284, 0.7470179071703249, 0.20355996950307709, 0.5666634960033603, -0.28181566223335369},
    {-0.021684656138120664, 0.01160765026381937, -0.012878192307465158, 0.74694791122660442, 0.20350793403824266, 0.56667513731661223, -0.28201529647325457},
    {-0.021691913823154722, 0.01148853849897079, -0.012735746615110493, 0.74687787973079889, 0.20345588888714858, 0.56668675165812665, -0.28221491729022236},
    {-0.02168848275998303, 0.011364242582863136, -0.012587684491753386, 0.74680781268624152, 0.20340383405227211, 0.56669833902735145, -0.28241452467475586},
    {-0.021655585052151212, 0.011225025723013335, -0.012423388468358568, 0.7467377100962671, 0.20335176953609083, 0.56670989942373484, -0.28261411861735453},
    {-0.021609094448383877, 0.011079452524003462, -0.012252231913174724, 0.74666757196421263, 0.2032996953410828, 0.56672143284672638, -0.28281369910851817},
    {-0.021542501607391441, 0.01092432819401189, -0.012070749517573779, 0.7465973982934162, 0.20324761146972661, 0.5667329392957775, -0.28301326613874767}};

const std::vector<std::array<double, 7>> kCowOverArmadillo = {
    {0.030178112376836326, 0.023466947023583339, -0.0089502692091641863, 0.78410826233430364, 0.23449817920122201, 0.55388591425004496, -0.15295499627597053},
    {0.030007274466067546, 0.023568065299715796, -0.0090618147789006918, 0.78405202805423291, 0.23444367843840752, 0.5539202017639302, -0.1532024445696597},
    {0.029832607453072028, 0.023667901399194679, -0.0091716281763956162, 0.78399574003608374, 0.23438916160707679, 0.55395445131272369, -0.15344988236301887},
    {0.029631633103460158, 0.023761517719669653, -0.0092726290294279298, 0.78393939828371384, 0.23433462871096628, 0.55398866289407778, -0.15369730963908904},
    {0.029437349769216647, 0.023856023035980008, -0.0093750448135162014, 0.783883002800985, 0.23428007975381362, 0.55402283650564788, -0.15394472638091175},
    {0.029284239081690915, 0.023959325019044193, -0.0094901344435824476, 0.78382655359176256, 0.23422551473935749, 0.55405697214509164, -0.15419213257152922},
    {0.029131616593771188, 0.024062365888526737, -0.0096049385280452728, 0.78377005065991534, 0.23417093367133776, 0.55409106981006917, -0.15443952819398468},
    {0.028979457149332991, 0.024165147024095248, -0.0097194573790098139, 0.783713494009316, 0.23411633655349545, 0.554125129498244, -0.15468691323132183},
    {0.028827777904714635, 0.024267679770902943, -0.0098337054368572794, 0.78365688364384112, 0.23406172338957235, 0.55415915120728121, -0.1549342876665851},
    {0.028676553647892376, 0.024369965368886685, -0.0099476828440772762, 0.78360021956737047, 0.23400709418331184, 0.55419313493484923, -0.1551816514828197},
    {0.028521328195895423, 0.024470890246444693, -0.010059825280605238, 0.78354350178378762, 0.2339524489384581, 0.55422708067861914, -0.15542900466307183},
    {0.028300365784859813, 0.024554585325501831, -0.010147933915516549, 0.78348673029698024, 0.23389778765875627, 0.55426098843626381, -0.15567634719038792},
    {0.028066411249807289, 0.024634187586732796, -0.010230472531818094, 0.78342990511083932, 0.23384311034795299, 0.55429485820545932, -0.15592367904781534}};

std::shared_ptr<const CollisionModel> LoadScaled(const std::string& file, double scale) {
  const std::string path = std::string(PD_TEST_MESH_DIR) + "/" + file;
  TriangleMesh mesh = LoadMesh(path).mesh;
  for (Vector3& v : mesh.vertices) v *= scale;
  return CollisionModel::Build(std::move(mesh));
}

void ExpectNoPocketsNoColdRestarts(const std::string& tool_file, double tool_scale,
                                   const std::string& object_file, double object_scale,
                                   const std::vector<std::array<double, 7>>& poses) {
  for (const std::string& f : {tool_file, object_file})
    PD_REQUIRE_FILE(std::string(PD_TEST_MESH_DIR) + "/" + f, "run scripts/fetch_meshes.sh");
  const auto tool = LoadScaled(tool_file, tool_scale);
  const auto object = LoadScaled(object_file, object_scale);
  PolyDepthSolver solver(tool, object);
  const Isometry3 X_WS = Isometry3::Identity();
  int pockets_escaped = 0;
  for (size_t i = 0; i < poses.size(); ++i) {
    const auto& p = poses[i];
    Isometry3 X_WP = Isometry3::Identity();
    X_WP.linear() = Quaternion(p[3], p[4], p[5], p[6]).normalized().toRotationMatrix();
    X_WP.translation() = Vector3(p[0], p[1], p[2]);
    const PenetrationResult r = solver.Solve(X_WP, X_WS, /*coherent=*/true);
    ASSERT_TRUE(r.in_collision) << "pose " << i;
    ASSERT_TRUE(r.valid) << "pose " << i;
    pockets_escaped += r.pocket_escapes;
    if (i > 0) {
      EXPECT_FALSE(r.warm_start_failed) << "pose " << i << " restarted cold";
    }
    const double size = ModelPair(*tool, *object, X_WP, X_WS).size();
    for (const double beyond : {0.0, 2e-6 * size}) {
      EXPECT_FALSE(ReferenceInCollision(tool->mesh(), X_WP, true, object->mesh(), X_WS, true,
                                        r.translation_W + beyond * r.normal_W))
          << "pose " << i << ": collides " << beyond << " m beyond the answer (depth "
          << r.depth << " m)";
    }
  }
  // The stretch does lead the solver into pockets: the check is exercised.
  EXPECT_GT(pockets_escaped, 0);
}

TEST(WarmPathPockets, FandiskOverElephant) {
  ExpectNoPocketsNoColdRestarts("fandisk.off", 0.034431803204303821, "refined_elephant.off", 0.12763984046501484,
                                kFandiskOverElephant);
}

TEST(WarmPathPockets, CowOverArmadillo) {
  ExpectNoPocketsNoColdRestarts("cow.off", 0.047510300737962564, "armadillo.off", 0.00080634978724717667,
                                kCowOverArmadillo);
}

// Work per query of a fast slide (bench_pd's 0.2 m/s): the cow tool goes on
// along the stretch's mean motion (0.23 mm per query, no turn) for 120
// queries, all in contact. Box plus triangle tests (deterministic): median
// 2675 before the lists kept separating axes and reached three queries of
// the motion, 1183 after. Every answer valid, none restarted cold, and every
// tenth checked free 2e-6 x size beyond by the reference.
TEST(WarmPathWork, CowSlidingFastOverArmadilloStaysCheap) {
  for (const std::string f : {"cow.off", "armadillo.off"})
    PD_REQUIRE_FILE(std::string(PD_TEST_MESH_DIR) + "/" + f, "run scripts/fetch_meshes.sh");
  const auto tool = LoadScaled("cow.off", 0.047510300737962564);
  const auto object = LoadScaled("armadillo.off", 0.00080634978724717667);
  PolyDepthSolver solver(tool, object);
  const auto& a = kCowOverArmadillo.front();
  const auto& b = kCowOverArmadillo.back();
  const Vector3 p_a(a[0], a[1], a[2]);
  const Vector3 v = (Vector3(b[0], b[1], b[2]) - p_a) / double(kCowOverArmadillo.size() - 1);
  const Isometry3 X_WS = Isometry3::Identity();
  std::vector<int64_t> work;
  for (int i = 0; i < 120; ++i) {
    Isometry3 X_WP = Isometry3::Identity();
    X_WP.linear() = Quaternion(a[3], a[4], a[5], a[6]).normalized().toRotationMatrix();
    X_WP.translation() = p_a + double(i) * v;
    const PenetrationResult r = solver.Solve(X_WP, X_WS, /*coherent=*/true);
    ASSERT_TRUE(r.in_collision) << "query " << i;
    ASSERT_TRUE(r.valid) << "query " << i;
    if (i == 0) continue;
    EXPECT_FALSE(r.warm_start_failed) << "query " << i << " restarted cold";
    work.push_back(r.box_tests + r.triangle_tests);
    if (i % 10 == 0) {
      const double beyond = 2e-6 * ModelPair(*tool, *object, X_WP, X_WS).size();
      EXPECT_FALSE(ReferenceInCollision(tool->mesh(), X_WP, true, object->mesh(), X_WS, true,
                                        r.translation_W + beyond * r.normal_W))
          << "query " << i;
    }
  }
  std::nth_element(work.begin(), work.begin() + work.size() / 2, work.end());
  EXPECT_LE(work[work.size() / 2], 1800) << "median box + triangle tests per query";
}

}  // namespace
}  // namespace pd
