// ROS 2 bags (#26): a rendered dataset exported with `depot export mcap`,
// read back by independent readers (the @mcap/core and
// @foxglove/rosmsg2-serialization packages, tests/mcap/check_bag.mjs) and
// compared message by message with the dataset's files; `depot slam run`
// on the bag equals the run on the folder; a bag @mcap/core wrote is read
// by ours; damaged and unusable bags are one error line each.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <zlib.h>
#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>

#include "common/binary_io.h"
#include "common/tum_io.h"
#include "dataset/boxes.h"
#include "dataset/label_images.h"
#include "dataset/mcap/mcap_records.h"
#include "dataset/mcap/mcap_writer.h"
#include "dataset/ros2/bag_layout.h"
#include "dataset/ros2/messages.h"
#include "slam/io/mcap_sequence.h"
#include "slam/io/settings.h"
#include "slam/io/tum_sequence.h"
#include "tests/support/cli_checks.h"
#include "tests/support/dataset_reader.h"
#include "tests/support/render_helpers.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace depot::test {
namespace {

using ::testing::HasSubstr;

const std::string kCheckDir = std::string(DEPOT_BINARY_DIR) + "/mcap-check";

// The pinned npm packages in the build folder, installed once (a lock keeps
// two test processes from installing at the same time).
void install_readers() {
  std::string out;
  const int code = run_command("cd " + kCheckDir +
                                   " && flock .install.lock sh -c 'test -d node_modules/@mcap/core "
                                   "|| npm ci --no-audit --no-fund --loglevel=error'",
                               &out);
  ASSERT_EQ(code, 0) << "npm ci of tests/mcap/package-lock.json failed:\n" << out;
}

std::vector<json> describe(const std::string& bag) {
  install_readers();
  std::string out;
  const int code = run_command("node " + kCheckDir + "/check_bag.mjs describe " + bag, &out);
  EXPECT_EQ(code, 0) << out.substr(0, 2000);
  std::vector<json> lines;
  std::istringstream in(out);
  std::string line;
  while (std::getline(in, line)) lines.push_back(json::parse(line));
  return lines;
}

uint32_t crc_of(const cv::Mat& m) {
  const cv::Mat dense = m.isContinuous() ? m : m.clone();
  return static_cast<uint32_t>(
      crc32(0, dense.data, static_cast<uInt>(dense.total() * dense.elemSize())));
}

uint64_t stamp_ns(const json& header) {
  return header["stamp"]["sec"].get<uint64_t>() * 1000000000u +
         header["stamp"]["nanosec"].get<uint64_t>();
}

// 20 walking_xyz frames at 160x120 (DEPOT_BAG_TEST_FRAMES / _WIDTH change
// that: 300 and 640 is the full check), and their bag.
int env_or(const char* name, int fallback) {
  const char* v = std::getenv(name);
  return v ? std::atoi(v) : fallback;
}
const int kFrames = env_or("DEPOT_BAG_TEST_FRAMES", 20);
struct Exported {
  std::string dataset, bag;
};
const Exported& exported() {
  static const Exported e = [] {
    Exported x{
        render_small({"depot_walking_xyz", kFrames, env_or("DEPOT_BAG_TEST_WIDTH", 160), false, 1}),
        temp_path("walking") + ".mcap"};
    const DepotResult r = depot("export mcap " + x.dataset + " -o " + x.bag + " -q");
    EXPECT_EQ(r.code, 0) << r.output;
    return x;
  }();
  return e;
}

TEST(McapBag, IndependentReadersDecodeEveryMessageAsTheDatasetHasIt) {
  const Exported& e = exported();
  const std::vector<json> lines = describe(e.bag);
  ASSERT_FALSE(lines.empty());
  const json& file = lines.front();
  EXPECT_EQ(file["profile"], "ros2");
  EXPECT_GT(file["chunks"].get<int>(), 0);
  EXPECT_NE(file["dataSectionCrc"].get<uint64_t>(), 0u);

  slam::TumSequence sequence(e.dataset);
  // Colour and labels carry the rgb stamps, depth its own clock's.
  std::map<uint64_t, size_t> frame_of, depth_frame_of;
  for (size_t i = 0; i < sequence.size(); ++i) {
    frame_of[mcap::nanoseconds_of(sequence.entry(i).rgb_timestamp)] = i;
    depth_frame_of[mcap::nanoseconds_of(sequence.entry(i).depth_timestamp)] = i;
  }
  std::map<uint64_t, StampedPose> truth;
  for (const StampedPose& p : read_tum_trajectory(e.dataset + "/groundtruth.txt"))
    truth[mcap::nanoseconds_of(p.timestamp)] = p;
  std::map<uint64_t, std::vector<dataset::BoxRecord>> boxes;
  for (const dataset::BoxRecord& b : dataset::read_boxes(e.dataset))
    boxes[mcap::nanoseconds_of(b.timestamp)].push_back(b);

  std::map<std::string, int> counts;
  cv::Mat bgr, depth, rgb;
  for (size_t k = 1; k < lines.size(); ++k) {
    const json& l = lines[k];
    const std::string topic = l["topic"];
    const json& m = l["message"];
    ++counts[topic];
    SCOPED_TRACE(topic + " message " + std::to_string(k));
    if (topic == ros2::kColourTopic || topic == ros2::kDepthTopic || topic == ros2::kLabelsTopic) {
      const uint64_t t = stamp_ns(m["header"]);
      ASSERT_EQ(std::to_string(t), l["logTime"].get<std::string>());
      const auto& frames = topic == ros2::kDepthTopic ? depth_frame_of : frame_of;
      ASSERT_TRUE(frames.count(t));
      const size_t i = frames.at(t);
      sequence.load(i, bgr, depth);
      if (topic == ros2::kColourTopic) {
        cv::cvtColor(bgr, rgb, cv::COLOR_BGR2RGB);
        EXPECT_EQ(m["encoding"], "rgb8");
        EXPECT_EQ(m["crc"].get<uint32_t>(), crc_of(rgb));
      } else if (topic == ros2::kDepthTopic) {
        EXPECT_EQ(m["encoding"], "32FC1");
        EXPECT_EQ(m["crc"].get<uint32_t>(), crc_of(depth));
      } else {
        const cv::Mat labels =
            dataset::read_label_image(e.dataset, dataset::label_image_name(sequence.timestamp(i)));
        EXPECT_EQ(m["encoding"], "16UC1");
        EXPECT_EQ(m["crc"].get<uint32_t>(), crc_of(labels));
      }
      EXPECT_EQ(m["width"].get<int>(), bgr.cols);
      EXPECT_EQ(m["height"].get<int>(), bgr.rows);
    } else if (topic == ros2::kColourInfoTopic) {
      EXPECT_EQ(m["k"][0].get<double>(),
                slam::load_settings(e.dataset + "/calibration.yaml").camera.fx);
      EXPECT_EQ(m["distortion_model"], "plumb_bob");
    } else if (topic == ros2::kTfTopic || topic == ros2::kTruthPoseTopic) {
      const json& at = topic == ros2::kTfTopic ? m["transforms"][0]["transform"] : m["pose"];
      const json& p = topic == ros2::kTfTopic ? at["translation"] : at["position"];
      const json& q = topic == ros2::kTfTopic ? at["rotation"] : at["orientation"];
      const uint64_t t =
          stamp_ns(topic == ros2::kTfTopic ? m["transforms"][0]["header"] : m["header"]);
      ASSERT_TRUE(truth.count(t));
      const Pose& pose = truth[t].pose;
      EXPECT_NEAR(p["x"].get<double>(), pose.translation().x(), 1e-12);
      EXPECT_NEAR(p["z"].get<double>(), pose.translation().z(), 1e-12);
      const Eigen::Quaterniond expected(pose.rotation());
      EXPECT_NEAR(
          std::abs(q["w"].get<double>() * expected.w() + q["x"].get<double>() * expected.x() +
                   q["y"].get<double>() * expected.y() + q["z"].get<double>() * expected.z()),
          1.0, 1e-12);
      if (topic == ros2::kTfTopic) {
        EXPECT_EQ(m["transforms"][0]["header"]["frame_id"], ros2::kWorldFrame);
        EXPECT_EQ(m["transforms"][0]["child_frame_id"], ros2::kTruthCameraFrame);
      }
    } else if (topic == ros2::kBoxesTopic) {
      const std::vector<dataset::BoxRecord>& expected = boxes[stamp_ns(m["header"])];
      ASSERT_EQ(m["detections"].size(), expected.size());
      for (size_t b = 0; b < expected.size(); ++b) {
        const json& d = m["detections"][b];
        const dataset::BoxRecord& r = expected[b];
        EXPECT_EQ(d["results"][0]["hypothesis"]["class_id"], r.class_name);
        EXPECT_EQ(d["bbox"]["center"]["position"]["x"].get<double>(), 0.5 * (r.x1 + r.x2));
        EXPECT_EQ(d["bbox"]["size_y"].get<double>(), r.y2 - r.y1);
        EXPECT_EQ(d["id"], std::to_string(r.id) + (r.moving ? " moving" : ""));
        EXPECT_EQ(d["results"][0]["hypothesis"]["score"].get<double>(),
                  static_cast<double>(r.visible_pixels) / r.area());
      }
    } else if (topic == ros2::kTruthPathTopic) {
      EXPECT_EQ(m["poses"].size(), truth.size());
    }
  }
  for (const char* topic :
       {ros2::kColourTopic, ros2::kDepthTopic, ros2::kColourInfoTopic, ros2::kDepthInfoTopic,
        ros2::kLabelsTopic, ros2::kBoxesTopic, ros2::kObjectsTopic})
    EXPECT_EQ(counts[topic], kFrames) << topic;
  EXPECT_EQ(counts[ros2::kTfTopic], static_cast<int>(truth.size()));
  EXPECT_EQ(counts[ros2::kTfStaticTopic], 1);
  EXPECT_EQ(counts[ros2::kTruthPathTopic], 1);
}

std::string without_first_line(const std::string& path) {
  std::ifstream in(path);
  std::string first, rest((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return rest.substr(rest.find('\n') + 1);
}

TEST(McapBag, SlamOnTheBagEqualsSlamOnTheFolder) {
  const Exported& e = exported();
  for (const std::string mode : {"orb", "full --detector darknet"}) {
    SCOPED_TRACE(mode);
    const std::string a = temp_path("folder") + ".txt", b = temp_path("bag") + ".txt";
    const DepotResult on_folder =
        depot("slam run " + e.dataset + " --mode " + mode + " --mapping sync -q -o " + a);
    const DepotResult on_bag =
        depot("slam run " + e.bag + " --mode " + mode + " --mapping sync -q -o " + b);
    ASSERT_EQ(on_folder.code, 0) << on_folder.output;
    ASSERT_EQ(on_bag.code, 0) << on_bag.output;
    // The first line names the input; every pose after it is the same text.
    const std::string folder_poses = without_first_line(a);
    EXPECT_GT(std::count(folder_poses.begin(), folder_poses.end(), '\n'), 15);
    EXPECT_EQ(without_first_line(b), folder_poses);
  }
}

TEST(McapBag, ABagWrittenByMcapCoreIsReadByOurs) {
  install_readers();
  const std::string bag = temp_path("foreign") + ".mcap";
  std::string out;
  const int code = run_command("node " + kCheckDir + "/check_bag.mjs write " + bag, &out);
  ASSERT_EQ(code, 0) << out;
  slam::BagTopics topics;
  topics.colour = "/cam/rgb";
  topics.depth = "/cam/depth";
  topics.colour_info = "/cam/rgb_info";
  const slam::McapSequence sequence(bag, topics);
  ASSERT_EQ(sequence.size(), 3u);  // depth 5 ms after colour: paired
  EXPECT_EQ(sequence.timestamp(2), 102.25);
  cv::Mat bgr, depth;
  sequence.load(1, bgr, depth);
  ASSERT_EQ(bgr.size(), cv::Size(40, 32));
  // bgr8 byte b = (b * 7 + frame) % 256; depth pixel i (500 + 10 i + frame) mm.
  EXPECT_EQ(bgr.at<cv::Vec3b>(0, 1)[0], (3 * 7 + 1) % 256);
  EXPECT_EQ(bgr.at<cv::Vec3b>(2, 5)[2], ((2 * 40 + 5) * 3 + 2) * 7 % 256 + 1);
  EXPECT_FLOAT_EQ(depth.at<float>(1, 2), (500 + 10 * 42 + 1) / 1000.0f);
  const auto camera = sequence.recorded_camera({});
  ASSERT_TRUE(camera.has_value());
  EXPECT_EQ(camera->fx, 5.0);
  EXPECT_EQ(camera->cy, 3.0);
  EXPECT_EQ(camera->lens.k1, 0.01);
}

// A tiny bag of our own making with one thing wrong.
std::string bag_with(const std::string& tag, const std::string& schema_encoding, bool with_depth,
                     double depth_offset) {
  const std::string path = temp_path(tag) + ".mcap";
  mcap::Writer w(path);
  const ros2::MessageType& type = ros2::image_type();
  const uint16_t s = w.add_schema(type.name, schema_encoding, type.definition);
  const uint16_t colour = w.add_channel(s, ros2::kColourTopic, "cdr");
  const uint16_t depth = with_depth ? w.add_channel(s, ros2::kDepthTopic, "cdr") : 0;
  for (int f = 0; f < 3; ++f) {
    const double t = 10.0 + f / 30.0;
    ros2::Image im;
    im.header.stamp = ros2::time_of(mcap::nanoseconds_of(t));
    im.width = 64;
    im.height = 48;
    im.encoding = "rgb8";
    im.step = 192;
    im.data = std::string(192 * 48, '\x40');
    w.write(colour, mcap::nanoseconds_of(t), mcap::nanoseconds_of(t), ros2::encode(im));
    if (!with_depth) continue;
    im.header.stamp = ros2::time_of(mcap::nanoseconds_of(t + depth_offset));
    im.encoding = "16UC1";
    im.step = 128;
    im.data = std::string(128 * 48, '\x10');
    w.write(depth, mcap::nanoseconds_of(t), mcap::nanoseconds_of(t), ros2::encode(im));
  }
  w.close();
  return path;
}

void expect_slam_error(const std::string& bag, const std::vector<std::string>& needles) {
  const std::string out = temp_path("traj") + ".txt";
  expect_one_error_line(depot("slam run " + bag + " -q -o " + out), needles);
  EXPECT_FALSE(fs::exists(out));
}

TEST(McapBag, DamagedOrUnusableBagsAreOneErrorLineEach) {
  const std::string good = bag_with("good", "ros2msg", true, 0.0);
  const std::string bytes = read_binary_file(good, "MCAP");

  const std::string truncated = temp_path("truncated") + ".mcap";
  std::ofstream(truncated, std::ios::binary) << bytes.substr(0, bytes.size() * 2 / 3);
  expect_slam_error(truncated, {truncated + ": truncated MCAP file"});

  std::string flipped = bytes;
  flipped[flipped.size() - 8 - 29 - 30] ^= 0x20;  // inside the summary
  const std::string bad_crc = temp_path("crc") + ".mcap";
  std::ofstream(bad_crc, std::ios::binary) << flipped;
  expect_slam_error(bad_crc, {bad_crc + ": summary CRC mismatch"});

  expect_slam_error(bag_with("protobuf", "protobuf", true, 0.0),
                    {"/camera/color/image_raw: unknown schema encoding 'protobuf'"});
  expect_slam_error(
      bag_with("no_depth", "ros2msg", false, 0.0),
      {"no depth topic /camera/depth/image_raw (the bag has: /camera/color/image_raw"});
  expect_slam_error(bag_with("unsynced", "ros2msg", true, 0.5),
                    {"colour and depth are not synchronised"});
  expect_slam_error(temp_path("absent") + ".mcap", {"no such MCAP file"});
}

}  // namespace
}  // namespace depot::test
