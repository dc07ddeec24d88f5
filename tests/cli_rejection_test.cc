// `depot eval rejection DATASET KEYPOINTS`: any system's per-keypoint file
// scored against a simulated dataset's labels. The built-in modes' own
// `--keypoints` file scores exactly as the run scored itself; files another
// program might write (keep everything; keep exactly what is off the movers)
// give the figures they must; bad files are one error line and no report.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/support/cli_checks.h"
#include "tests/support/dataset_reader.h"
#include "tests/support/render_helpers.h"

namespace fs = std::filesystem;

namespace depot::test {
namespace {

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream s(line);
  std::string field;
  while (std::getline(s, field, ',')) out.push_back(field);
  if (!line.empty() && line.back() == ',') out.push_back("");
  return out;
}

// A CSV read by column name (independently of eval/keypoint_file.h).
struct Csv {
  std::map<std::string, size_t> column;
  std::vector<std::vector<std::string>> rows;
  const std::string& at(size_t row, const std::string& name) const {
    return rows[row].at(column.at(name));
  }
};

Csv read_csv(const std::string& path) {
  Csv csv;
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  const std::vector<std::string> names = split(line);
  for (size_t i = 0; i < names.size(); ++i) csv.column[names[i]] = i;
  while (std::getline(in, line)) csv.rows.push_back(split(line));
  return csv;
}

// A masked run of 12 walking frames with its own keypoint file, statistics
// and printed scores; made once for the tests of this process.
struct OwnRun {
  std::string dataset, keypoints, stats, output;
};

const OwnRun& own_run() {
  static const OwnRun run = [] {
    OwnRun r;
    r.dataset = render_small({"depot_walking_xyz", 12, 320, false});
    r.keypoints = temp_path("kps") + ".csv";
    r.stats = temp_path("stats") + ".csv";
    const DepotResult d = depot("slam run " + r.dataset + " -o " + temp_path("traj") +
                                ".txt --mode masked --mapping sync -q --keypoints " + r.keypoints +
                                " --stats " + r.stats);
    EXPECT_EQ(d.code, 0) << d.output;
    r.output = d.output;
    return r;
  }();
  return run;
}

// `depot eval rejection` with a JSON report, which it returns.
nlohmann::json score(const std::string& dataset, const std::string& keypoints,
                     std::string* printed = nullptr) {
  const std::string json = temp_path("rejection") + ".json";
  const DepotResult r = depot("eval rejection " + dataset + " " + keypoints + " --json " + json);
  EXPECT_EQ(r.code, 0) << r.output;
  if (printed) *printed = r.output;
  std::ifstream in(json);
  return nlohmann::json::parse(in);
}

// Writes the own run's keypoints as another program might: its columns, and
// `kept` decided from the run's row (by column name).
template <typename Kept>
std::string rewrite(const std::string& tag, const std::string& header, const Kept& kept,
                    bool octave) {
  const Csv own = read_csv(own_run().keypoints);
  const std::string path = temp_path(tag) + ".csv";
  std::ofstream out(path);
  out << header << "\n";
  for (size_t i = 0; i < own.rows.size(); ++i) {
    out << own.at(i, "timestamp") << ',' << own.at(i, "x") << ',' << own.at(i, "y") << ',';
    if (octave) out << own.at(i, "octave") << ",0.5,O,";
    out << kept(own, i) << "\n";
  }
  return path;
}

TEST(CliRejection, ScoresTheBuiltInModesOwnFileAsTheRunScoredItself) {
  const OwnRun& run = own_run();
  // The run's printed figures.
  double precision = 0, recall = 0, precision_static = 0;
  long fp_printed = 0, static_points = 0, boundary_fp = 0;
  const size_t at = run.output.find("rejection vs ground truth: ");
  ASSERT_NE(at, std::string::npos) << run.output;
  ASSERT_EQ(std::sscanf(run.output.c_str() + at,
                        "rejection vs ground truth: precision %lf recall %lf with boundary points "
                        "left out; precision %lf with them counted as static (%ld of %ld static "
                        "points thrown away, %ld of",
                        &precision, &recall, &precision_static, &fp_printed, &static_points,
                        &boundary_fp),
            6)
      << run.output;
  // Its per-frame counts, summed.
  const Csv stats = read_csv(run.stats);
  ASSERT_EQ(stats.rows.size(), 12u);
  long tp = 0, fp = 0, fn = 0;
  for (size_t i = 0; i < stats.rows.size(); ++i) {
    tp += std::stol(stats.at(i, "true_positive"));
    fp += std::stol(stats.at(i, "false_positive"));
    fn += std::stol(stats.at(i, "false_negative"));
  }
  // And the truth columns the run wrote beside each keypoint.
  const Csv own = read_csv(run.keypoints);
  long own_btn = 0, own_bfp = 0;
  for (size_t i = 0; i < own.rows.size(); ++i)
    if (own.at(i, "boundary") == "1") (own.at(i, "kept") == "1" ? own_btn : own_bfp)++;

  std::string printed;
  const nlohmann::json s = score(run.dataset, run.keypoints, &printed);
  EXPECT_EQ(s["true_positive"].get<long>(), tp) << printed;
  EXPECT_EQ(s["false_positive"].get<long>(), fp) << printed;
  EXPECT_EQ(s["false_positive"].get<long>(), fp_printed);
  EXPECT_EQ(s["false_negative"].get<long>(), fn) << printed;
  EXPECT_EQ(s["true_negative"].get<long>(), static_points - fp_printed) << printed;
  EXPECT_EQ(s["boundary_false_positive"].get<long>(), boundary_fp);
  EXPECT_EQ(s["boundary_false_positive"].get<long>(), own_bfp);
  EXPECT_EQ(s["boundary_true_negative"].get<long>(), own_btn);
  EXPECT_EQ(s["keypoints_scored"].get<size_t>(), own.rows.size());
  EXPECT_EQ(s["frames_scored"].get<size_t>(), 12u);
  EXPECT_NEAR(s["precision_without_boundary"].get<double>(), precision, 5e-4) << printed;
  EXPECT_NEAR(s["precision"].get<double>(), precision_static, 5e-4) << printed;
  EXPECT_NEAR(s["recall"].get<double>(), recall, 5e-4) << printed;
  EXPECT_GT(tp, 0);  // people walk through, and masked rejects them
  EXPECT_GT(fn + fp, 0);
  EXPECT_THAT(printed, ::testing::HasSubstr("true positive  " + std::to_string(tp) + " "))
      << printed;
  std::printf(
      "own file: TP %ld FP %ld FN %ld TN %ld (boundary FP %ld TN %ld), precision %.4f "
      "(%.4f without boundary) recall %.4f\n",
      tp, fp, fn, s["true_negative"].get<long>(), own_bfp, own_btn, s["precision"].get<double>(),
      s["precision_without_boundary"].get<double>(), s["recall"].get<double>());
}

TEST(CliRejection, KeepingEverythingRecallsNothing) {
  const std::string keep_all = rewrite(
      "keep_all", "timestamp,x,y,kept", [](const Csv&, size_t) { return "1"; }, false);
  std::string printed;
  const nlohmann::json s = score(own_run().dataset, keep_all, &printed);
  EXPECT_EQ(s["true_positive"].get<long>(), 0);
  EXPECT_EQ(s["false_positive"].get<long>(), 0);
  EXPECT_GT(s["false_negative"].get<long>(), 0);
  EXPECT_TRUE(s["precision"].is_null());
  EXPECT_TRUE(s["precision_without_boundary"].is_null());
  EXPECT_EQ(s["recall"].get<double>(), 0.0);
  EXPECT_FALSE(s["octave_column"].get<bool>());
  EXPECT_NE(printed.find("precision      undefined (boundary"), std::string::npos) << printed;
  EXPECT_THAT(printed, ::testing::HasSubstr("recall         0.0000")) << printed;
}

TEST(CliRejection, RejectingExactlyTheMoversIsPerfect) {
  const std::string oracle = rewrite(
      "oracle", "timestamp,x,y,octave,response,set,kept",
      [](const Csv& own, size_t i) { return own.at(i, "on_moving") == "1" ? "0" : "1"; }, true);
  const nlohmann::json s = score(own_run().dataset, oracle);
  EXPECT_GT(s["true_positive"].get<long>(), 0);
  EXPECT_EQ(s["false_positive"].get<long>(), 0);
  EXPECT_EQ(s["false_negative"].get<long>(), 0);
  EXPECT_EQ(s["precision"].get<double>(), 1.0);
  EXPECT_EQ(s["precision_without_boundary"].get<double>(), 1.0);
  EXPECT_EQ(s["recall"].get<double>(), 1.0);
}

TEST(CliRejection, BadInputIsOneErrorLineAndNoReport) {
  const OwnRun& run = own_run();
  const Csv own = read_csv(run.keypoints);
  const std::string t = own.at(0, "timestamp");
  auto expect_error = [&](const std::string& dataset, const std::string& text,
                          const std::string& needle) {
    const std::string file = temp_path("bad") + ".csv", json = temp_path("bad") + ".json";
    std::ofstream(file) << text;
    const DepotResult r = depot("eval rejection " + dataset + " " + file + " --json " + json);
    expect_one_error_line(r, needle);
    EXPECT_FALSE(fs::exists(json)) << "no report on failure";
  };
  const std::string header = "timestamp,x,y,kept\n", good = t + ",10,10,1\n";
  expect_error(run.dataset, header + good + "12345.5,10,10,1\n",
               ":3: timestamp 12345.5 is not a frame of " + run.dataset);
  expect_error(run.dataset, header + good + t + ",320,10,1\n",
               ":3: point (320, 10) is outside the 320x240 image");
  expect_error(run.dataset, "timestamp,x,y\n" + t + ",10,10\n",
               ":1: the header has no 'kept' column");
  expect_error(run.dataset, header + t + ",10,10,2\n",
               ":2: kept must be 0 (rejected) or 1 (kept), got '2'");
  // A dataset without labels has nothing to score against.
  const std::string real = temp_path("real");
  fs::create_directories(real);
  expect_error(real, header + good, "not a simulated dataset");
}

// Movers without a detection: with a detector that finds nothing, masked
// rejects nothing, unless motion-found objects are on; then the cat walking
// before the patrol's camera is rejected by its motion alone.
TEST(CliRejection, MotionFindsMoversNoDetectorNamed) {
  const std::string dataset = render_small({"depot_patrol", 40, 320, false, 1});
  auto with_depth = [&](const std::string& extra, double* precision, double* recall) {
    const DepotResult r =
        depot("slam run " + dataset + " -o " + temp_path("movers") +
              ".txt --mode masked --mapping sync -q --detector-set miss_rate=1" + extra);
    ASSERT_EQ(r.code, 0) << r.output;
    const size_t at = r.output.find("keypoints with depth");
    ASSERT_NE(at, std::string::npos) << r.output;
    const std::string line = r.output.substr(at, r.output.find('\n', at) - at);
    char p[16] = {}, q[16] = {};
    ASSERT_EQ(
        std::sscanf(line.c_str() + line.find("precision"), "precision %15s recall %15s", p, q), 2)
        << line;
    *precision = std::atof(p);  // "nan" when nothing was rejected
    *recall = std::atof(q);
  };
  double precision = 0, recall = 1;
  with_depth("", &precision, &recall);
  EXPECT_EQ(recall, 0.0);
  with_depth(" --rejection-set motion=true", &precision, &recall);
  EXPECT_GE(recall, 0.3);      // 0.40 measured
  EXPECT_GE(precision, 0.75);  // 0.84 measured
}

}  // namespace
}  // namespace depot::test
