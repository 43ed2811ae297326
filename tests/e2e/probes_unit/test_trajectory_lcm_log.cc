// LCM log trajectories: pose channel only, LCM_SELF_TEST skipped, sample time
// from the pose utime; format detection by the log magic number.
#include <gtest/gtest.h>

#include <lcm/lcm-cpp.hpp>
#include <string>
#include <vector>

#include "haptics_msgs/probe_pose_t.hpp"
#include "haptics_msgs/probe_pose_v1_t.hpp"
#include "haptics_msgs/wrench_t.hpp"
#include "probes/trajectory/input_error.h"
#include "probes/trajectory/load_trajectory.h"
#include "probes/transport/log_upgrade.h"
#include "probes/trajectory/trajectory_lcm_log.h"
#include "temp_file.h"

namespace probes {
namespace {

void WriteEvent(lcm::LogFile* log, const std::string& channel, std::vector<uint8_t> data) {
  static int64_t eventnum = 0;
  lcm::LogEvent e{};
  e.eventnum = eventnum++;
  e.timestamp = 1'700'000'000'000'000 + eventnum;
  e.channel = channel;
  e.datalen = static_cast<int32_t>(data.size());
  e.data = data.data();
  ASSERT_EQ(log->writeEvent(&e), 0);
}

template <typename Msg>
std::vector<uint8_t> Encode(const Msg& msg) {
  std::vector<uint8_t> buf(msg.getEncodedSize());
  msg.encode(buf.data(), 0, static_cast<int>(buf.size()));
  return buf;
}

haptics_msgs::probe_pose_t Pose(int64_t seq, int64_t utime, double z, int64_t session = 0x5e55,
                                const std::string& device = "sigma7") {
  haptics_msgs::probe_pose_t p{};
  p.version = haptics_msgs::probe_pose_t::VERSION;
  p.sender_session = session;
  p.sender_device = device;
  p.seq = seq;
  p.utime = utime;
  p.position[2] = z;
  p.orientation[0] = 1.0;
  p.has_velocity = true;
  p.linear_velocity[2] = -0.01;
  return p;
}

TEST(TrajectoryLcmLog, ReadsPoseChannelOnly) {
  const std::string path = TempPath("poses.lcmlog");
  {
    lcm::LogFile log(path, "w");
    ASSERT_TRUE(log.good());
    WriteEvent(&log, "LCM_SELF_TEST", {1, 2, 3});
    WriteEvent(&log, "PROBE_POSE", Encode(Pose(7, 5'000'000, 0.10)));
    WriteEvent(&log, "HAPTIC_WRENCH", Encode(haptics_msgs::wrench_t{}));
    WriteEvent(&log, "PROBE_POSE", Encode(Pose(8, 5'001'000, 0.09)));
  }
  EXPECT_TRUE(IsLcmLogFile(path));
  const Trajectory t = LoadTrajectory(path, "PROBE_POSE");
  ASSERT_EQ(t.size(), 2u);
  EXPECT_DOUBLE_EQ(t[0].t, 0.0);
  EXPECT_DOUBLE_EQ(t[1].t, 0.001);
  EXPECT_DOUBLE_EQ(t[1].p_WP[2], 0.09);
  EXPECT_TRUE(t[1].has_velocity);
  EXPECT_DOUBLE_EQ(t[1].v_WP[2], -0.01);
}

TEST(TrajectoryLcmLog, UndecodablePoseNamesEvent) {
  const std::string path = TempPath("bad.lcmlog");
  {
    lcm::LogFile log(path, "w");
    WriteEvent(&log, "PROBE_POSE", Encode(Pose(1, 10, 0.1)));
    WriteEvent(&log, "PROBE_POSE", Encode(haptics_msgs::wrench_t{}));  // wrong type
  }
  try {
    ReadTrajectoryLcmLog(path, "PROBE_POSE");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(path + ": event 2"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("cannot decode"), std::string::npos) << e.what();
  }
}

TEST(TrajectoryLcmLog, MissingChannelListsWhatIsThere) {
  const std::string path = TempPath("nopose.lcmlog");
  {
    lcm::LogFile log(path, "w");
    WriteEvent(&log, "LCM_SELF_TEST", {0});
    WriteEvent(&log, "OTHER", {0});
  }
  try {
    ReadTrajectoryLcmLog(path, "PROBE_POSE");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("channels in the log: OTHER (1)"), std::string::npos)
        << e.what();
  }
}

TEST(TrajectoryLcmLog, NonIncreasingUtimeIsAnError) {
  const std::string path = TempPath("time.lcmlog");
  {
    lcm::LogFile log(path, "w");
    WriteEvent(&log, "PROBE_POSE", Encode(Pose(1, 10, 0.1)));
    WriteEvent(&log, "PROBE_POSE", Encode(Pose(2, 10, 0.1)));
  }
  EXPECT_THROW(ReadTrajectoryLcmLog(path, "PROBE_POSE"), InputError);
}

TEST(TrajectoryLcmLog, AVersionOneLogIsRejectedNamingTheConverter) {
  const std::string path = TempPath("v1.lcmlog");
  {
    lcm::LogFile log(path, "w");
    haptics_msgs::probe_pose_v1_t old{};
    old.seq = 1;
    old.utime = 10;
    old.orientation[0] = 1.0;
    WriteEvent(&log, "PROBE_POSE", Encode(old));
  }
  try {
    ReadTrajectoryLcmLog(path, "PROBE_POSE");
    FAIL() << "no error";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(path + ": event 1"), std::string::npos) << what;
    EXPECT_NE(what.find("version 1"), std::string::npos) << what;
    EXPECT_NE(what.find("probe_log_upgrade"), std::string::npos) << what;
  }
}

TEST(TrajectoryLcmLog, ALogOfTwoSendersNeedsOneChosen) {
  const std::string path = TempPath("two_senders.lcmlog");
  {
    lcm::LogFile log(path, "w");
    // Interleaved, as a log recorded while two clients published looks.
    for (int64_t k = 0; k < 4; ++k) {
      WriteEvent(&log, "PROBE_POSE", Encode(Pose(k, 1000 * (k + 1), 0.01, 0xaaaa, "sigma7")));
      WriteEvent(&log, "PROBE_POSE", Encode(Pose(k, 1000 * (k + 1) + 500, 0.05, 0xbbbb, "probe_sim")));
    }
  }
  try {
    ReadTrajectoryLcmLog(path, "PROBE_POSE");
    FAIL() << "no error";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("2 senders"), std::string::npos) << what;
    EXPECT_NE(what.find("0x000000000000aaaa 'sigma7' (4 poses)"), std::string::npos) << what;
    EXPECT_NE(what.find("0x000000000000bbbb 'probe_sim' (4 poses)"), std::string::npos) << what;
    EXPECT_NE(what.find("--log-session"), std::string::npos) << what;
  }
  const Trajectory b = LoadTrajectory(path, "PROBE_POSE", 0xbbbb);
  ASSERT_EQ(b.size(), 4u);
  for (const PoseSample& s : b) EXPECT_DOUBLE_EQ(s.p_WP[2], 0.05);
  EXPECT_DOUBLE_EQ(b[3].t, 0.003);
  EXPECT_THROW(ReadTrajectoryLcmLog(path, "PROBE_POSE", 0xcccc), InputError);
}

TEST(LogUpgrade, AVersionOneLogConvertedReadsBackWithTheSameMotion) {
  const std::string old_path = TempPath("upgrade_v1.lcmlog");
  const std::string new_path = TempPath("upgrade_v2.lcmlog");
  const std::vector<uint8_t> wrench_bytes = Encode(haptics_msgs::wrench_t{});
  {
    lcm::LogFile log(old_path, "w");
    WriteEvent(&log, "LCM_SELF_TEST", {9, 8, 7});
    for (int64_t k = 0; k < 3; ++k) {
      haptics_msgs::probe_pose_v1_t old{};
      old.seq = 10 + k;
      old.utime = 2'000'000 + 1000 * k;
      old.position[0] = 0.001 * k;
      old.position[2] = 0.02;
      old.orientation[0] = 1.0;
      old.has_velocity = true;
      old.linear_velocity[0] = 1.0;
      WriteEvent(&log, "PROBE_POSE", Encode(old));
      WriteEvent(&log, "HAPTIC_WRENCH", wrench_bytes);
    }
  }
  EXPECT_THROW(ReadTrajectoryLcmLog(old_path, "PROBE_POSE"), InputError);
  const LogUpgradeCounts n = UpgradePoseLog(old_path, new_path, "PROBE_POSE", MakeSender("0x1234", "old_rig"));
  EXPECT_EQ(n.upgraded, 3);
  EXPECT_EQ(n.already, 0);
  EXPECT_EQ(n.copied, 4);
  const Trajectory t = ReadTrajectoryLcmLog(new_path, "PROBE_POSE");
  ASSERT_EQ(t.size(), 3u);
  EXPECT_DOUBLE_EQ(t[2].t, 0.002);
  EXPECT_DOUBLE_EQ(t[2].p_WP[0], 0.002);
  EXPECT_DOUBLE_EQ(t[2].p_WP[2], 0.02);
  EXPECT_DOUBLE_EQ(t[1].v_WP[0], 1.0);
  // Identity on every pose; other events byte for byte.
  lcm::LogFile log(new_path, "r");
  int poses = 0, wrenches = 0;
  for (const lcm::LogEvent* e = log.readNextEvent(); e != nullptr; e = log.readNextEvent()) {
    if (e->channel == "PROBE_POSE") {
      haptics_msgs::probe_pose_t p{};
      ASSERT_EQ(p.decode(e->data, 0, e->datalen), e->datalen);
      EXPECT_EQ(p.version, int{haptics_msgs::probe_pose_t::VERSION});
      EXPECT_EQ(p.sender_session, 0x1234);
      EXPECT_EQ(p.sender_device, "old_rig");
      EXPECT_EQ(p.seq, 10 + poses++);
    } else if (e->channel == "HAPTIC_WRENCH") {
      ++wrenches;
      EXPECT_EQ(std::vector<uint8_t>(static_cast<const uint8_t*>(e->data),
                                     static_cast<const uint8_t*>(e->data) + e->datalen),
                wrench_bytes);
    }
  }
  EXPECT_EQ(poses, 3);
  EXPECT_EQ(wrenches, 3);
}

TEST(LogUpgrade, GarbageOnThePoseChannelIsAnErrorNamingTheEvent) {
  const std::string old_path = TempPath("upgrade_bad.lcmlog");
  {
    lcm::LogFile log(old_path, "w");
    WriteEvent(&log, "PROBE_POSE", {1, 2, 3});
  }
  try {
    UpgradePoseLog(old_path, old_path + ".out", "PROBE_POSE", MakeSender("", "x"));
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("event 1 on 'PROBE_POSE' is neither"), std::string::npos) << e.what();
  }
}

TEST(TrajectoryLcmLog, CsvIsNotMistakenForALog) {
  const std::string path = WriteTempFile("plain.csv", "time,x,y,z,qw,qx,qy,qz\n0,1,2,3,1,0,0,0\n");
  EXPECT_FALSE(IsLcmLogFile(path));
  EXPECT_DOUBLE_EQ(LoadTrajectory(path, "PROBE_POSE").at(0).p_WP[2], 3.0);
}

}  // namespace
}  // namespace probes
