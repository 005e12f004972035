// The HTML replay writer: byte codec round trips, the embedded JSON, self-containment.
#include "bipednav/viz/replay_html.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <regex>

#include "bipednav/common/error.hpp"
#include "bipednav/viz/byte_codec.hpp"

using namespace bipednav;
using namespace bipednav::viz;

namespace {

std::vector<std::uint8_t> bytes(std::string_view s) { return {s.begin(), s.end()}; }

ReplayData two_frame_replay() {
  ReplayData d;
  d.title = "test <run>";
  d.summary.scenario = "unit";
  d.summary.success = true;
  d.summary.outcome = "SUCCESS";
  d.robot_radius_m = 0.25;
  d.statics = {{{0, 0}, {1, 0}, {1, 1}}};
  d.actors = {{"box", {{{-0.1, -0.1}, {0.1, -0.1}, {0.1, 0.1}}}}};
  d.goals = {{0.0, {2.0, 1.0, 0.5}}};
  for (int i = 0; i < 3; ++i) {
    ReplayFrame f;
    f.t_s = 0.1 * i;
    f.true_pose = {0.5 * i, 0.25, 0.1};
    f.estimated_pose = {0.5 * i + 0.01, 0.25, 0.1};
    f.goal = d.goals[0].pose;
    f.global_path.poses = {{0.5 * i, 0.25, 0}, {2.0, 1.0, 0}};
    f.local_trajectory.poses = {{0, 0, 0}, {0.3, 0, 0}};  // the same in every frame
    f.actors = {{1.0, 1.0 + i, 0.0}};
    f.lidar = {{1.234f, -2.5f}, {std::nanf(""), 0.0f}, {400.0f, 0.0f}};  // NaN and out-of-range dropped
    f.active_node = "FollowPath";
    f.state = "ACTIVE";
    d.frames.push_back(f);
  }
  ReplayGrid g{0.0, 3, 2, 0.1, -1.0, -2.0, {0, 254, 255, 253, 10, 0}};
  d.global_maps = {g};
  d.local_maps = {g, g};
  return d;
}

nlohmann::json embedded_json(const std::string& html) {
  const std::string open = "<script id=\"replay-data\" type=\"application/json\">";
  const auto a = html.find(open);
  EXPECT_NE(a, std::string::npos);
  const auto b = html.find("</script>", a);
  return nlohmann::json::parse(html.substr(a + open.size(), b - a - open.size()));
}

}  // namespace

TEST(ByteCodec, Base64KnownVectors) {
  EXPECT_EQ(base64_encode(bytes("")), "");
  EXPECT_EQ(base64_encode(bytes("f")), "Zg==");
  EXPECT_EQ(base64_encode(bytes("fo")), "Zm8=");
  EXPECT_EQ(base64_encode(bytes("foobar")), "Zm9vYmFy");
  EXPECT_EQ(base64_decode("Zm9vYg=="), bytes("foob"));
  EXPECT_EQ(base64_decode("Zm9vYmE="), bytes("fooba"));
  EXPECT_THROW(base64_decode("Zm9"), Error);
  EXPECT_THROW(base64_decode("Zm9!"), Error);
  EXPECT_THROW(base64_decode("Z=9v"), Error);
}

TEST(ByteCodec, DeflateRoundTripAndCompressesRepeats) {
  std::vector<std::uint8_t> cells(10000, 0);
  for (std::size_t i = 0; i < cells.size(); i += 97) cells[i] = 254;
  const auto packed = pack_bytes(cells);
  EXPECT_LT(packed.size(), 1000u);
  EXPECT_EQ(unpack_bytes(packed), cells);
  EXPECT_EQ(pack_bytes({}), "");
  EXPECT_TRUE(unpack_bytes("").empty());
  EXPECT_THROW(inflate_bytes(bytes("not zlib")), Error);
}

TEST(ReplayHtml, IsSelfContained) {
  const std::string html = replay_html(two_frame_replay());
  EXPECT_EQ(html.rfind("<!DOCTYPE html>", 0), 0u);
  EXPECT_EQ(html.find("{{REPLAY_DATA}}"), std::string::npos);
  const std::regex remote(R"((src|href)\s*=\s*["']?\s*(https?:)?//)", std::regex::icase);
  EXPECT_FALSE(std::regex_search(html, remote));
  EXPECT_EQ(html.find("<link"), std::string::npos);
  EXPECT_EQ(html.find("@import"), std::string::npos);
  // The title's '<' is escaped inside the JSON, so it cannot close the script element.
  EXPECT_EQ(html.find("test <run>"), std::string::npos);
}

TEST(ReplayHtml, JsonHasFramesPathsOnlyWhenChangedAndPackedPayloads) {
  const nlohmann::json j = embedded_json(replay_html(two_frame_replay()));
  EXPECT_EQ(j["format"], "bipednav-replay");
  EXPECT_EQ(j["title"], "test <run>");
  EXPECT_DOUBLE_EQ(j["robot_radius_m"].get<double>(), 0.25);
  ASSERT_EQ(j["frames"].size(), 3u);
  const auto& f1 = j["frames"][1];
  EXPECT_DOUBLE_EQ(f1["t"].get<double>(), 0.1);
  EXPECT_DOUBLE_EQ(f1["true"][0].get<double>(), 0.5);
  EXPECT_DOUBLE_EQ(f1["est"][0].get<double>(), 0.51);
  EXPECT_EQ(f1["node"], "FollowPath");
  EXPECT_EQ(f1["actors"][0][1].get<double>(), 2.0);
  // The global path changes every frame, the local trajectory and the points only in the first.
  EXPECT_TRUE(f1.contains("gp"));
  EXPECT_EQ(f1["gp"][0].get<double>(), 0.5);
  EXPECT_TRUE(j["frames"][0].contains("lt"));
  EXPECT_FALSE(f1.contains("lt"));
  // Points: int16 pairs of centimetres, only when they changed; NaN and out-of-range points are dropped.
  EXPECT_FALSE(f1.contains("lidar"));
  const auto pts = unpack_bytes(j["frames"][0]["lidar"].get<std::string>());
  ASSERT_EQ(pts.size(), 4u);
  EXPECT_EQ(static_cast<std::int16_t>(pts[0] | pts[1] << 8), 123);
  EXPECT_EQ(static_cast<std::int16_t>(pts[2] | pts[3] << 8), -250);
  EXPECT_DOUBLE_EQ(j["point_step_m"].get<double>(), 0.01);
  // Grids round-trip.
  ASSERT_EQ(j["local_maps"].size(), 2u);
  const auto& g = j["global_maps"][0];
  EXPECT_EQ(g["w"], 3);
  EXPECT_EQ(g["h"], 2);
  EXPECT_EQ(unpack_bytes(g["cells"].get<std::string>()), (std::vector<std::uint8_t>{0, 254, 255, 253, 10, 0}));
}

TEST(ReplayHtml, FootstepLayerOnlyForFootstepRuns) {
  const nlohmann::json wheeled = embedded_json(replay_html(two_frame_replay()));
  EXPECT_FALSE(wheeled.contains("footsteps"));
  EXPECT_FALSE(wheeled.contains("height_maps"));
  EXPECT_FALSE(wheeled["frames"][0].contains("plan"));

  ReplayData d = two_frame_replay();
  ReplayFootsteps fs;
  fs.foot_length_m = 0.16;
  fs.taken = {
      {0.0, true, {0.0, 0.05, 0.0}, ""}, {0.0, false, {0.0, -0.05, 0.0}, ""}, {0.6, true, {0.1, 0.05, 0.0}, "planar"}};
  fs.height_maps = {{0.0, 3, 2, 0.01, -1.0, -2.0, {0, 254, 255, 255, 10, 0}}};
  fs.height_lo_m = -0.01;
  fs.height_hi_m = 0.5;
  d.footsteps = fs;
  const std::vector<ReplayFoot> plan = {{0.0, false, {0.2, -0.05, 0.0}, "step_onto"},
                                        {0.0, true, {0.3, 0.05, 0.1}, "planar"}};
  d.frames[0].plan = plan;
  d.frames[0].replanned = true;
  d.frames[1].plan = plan;  // unchanged: not repeated
  d.frames[2].plan = {plan[1]};
  const nlohmann::json j = embedded_json(replay_html(d));
  ASSERT_TRUE(j.contains("footsteps"));
  EXPECT_DOUBLE_EQ(j["footsteps"]["foot"][0].get<double>(), 0.16);
  ASSERT_EQ(j["footsteps"]["taken"].size(), 3u);
  EXPECT_EQ(j["footsteps"]["taken"][2], nlohmann::json::parse(R"([0.6, 1, 0.1, 0.05, 0.0, "planar"])"));
  EXPECT_DOUBLE_EQ(j["footsteps"]["height_hi"].get<double>(), 0.5);
  ASSERT_EQ(j["height_maps"].size(), 1u);
  EXPECT_EQ(unpack_bytes(j["height_maps"][0]["cells"].get<std::string>()),
            (std::vector<std::uint8_t>{0, 254, 255, 255, 10, 0}));
  const auto& frames = j["frames"];
  EXPECT_EQ(frames[0]["plan"],
            nlohmann::json::parse(R"([[0, 0.2, -0.05, 0.0, "step_onto"], [1, 0.3, 0.05, 0.1, "planar"]])"));
  EXPECT_TRUE(frames[0].value("replan", false));
  EXPECT_FALSE(frames[1].contains("plan"));
  EXPECT_FALSE(frames[1].contains("replan"));
  EXPECT_EQ(frames[2]["plan"].size(), 1u);
}

TEST(ReplayHtml, RejectsInconsistentData) {
  ReplayData d = two_frame_replay();
  d.global_maps[0].cells.pop_back();
  EXPECT_THROW(replay_html(d), ParamError);
  d = two_frame_replay();
  d.frames[0].actors.clear();
  EXPECT_THROW(replay_html(d), ParamError);
  ReplayHtmlParams p;
  p.position_resolution_m = 0.0;
  EXPECT_THROW(replay_html(two_frame_replay(), p), ParamError);
}

TEST(ReplayHtml, WritesTheFile) {
  const auto file = std::filesystem::temp_directory_path() / "bipednav_replay_test" / "replay.html";
  write_replay_html(file, two_frame_replay());
  EXPECT_GT(std::filesystem::file_size(file), 1000u);
  std::filesystem::remove_all(file.parent_path());
  EXPECT_THROW(write_replay_html("/proc/no/such/dir/replay.html", two_frame_replay()), Error);
}
