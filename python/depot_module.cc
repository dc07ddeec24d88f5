// `import depot`: the simulator, the SLAM and the evaluation from Python,
// with NumPy arrays in and out. Each function is a thin layer over the
// library the `depot` program uses (no second copy of a format or a loop):
// render_dataset (sim/pipeline), Sequence (slam/io: TUM folders and ROS 2
// bags), Slam (tools/runner prepare_run + slam::System, fed frame by frame),
// slam_run (tools/runner run_sequence), ate (eval/), export_mcap (tools/bag).
// The GIL is released while rendering and tracking; depot::Error becomes
// depot.Error with the same one-line message.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <filesystem>
#include <fstream>
#include <map>

#include <opencv2/imgproc.hpp>

#include "common/child_process.h"
#include "common/error.h"
#include "common/mutex.h"
#include "common/tum_association.h"
#include "common/tum_io.h"
#include "common/yaml_overrides.h"
#include "dataset/boxes.h"
#include "dataset/dataset_files.h"
#include "dataset/label_images.h"
#include "dataset/ros2/bag_trajectory.h"
#include "eval/ate.h"
#include "eval/matched_trajectories.h"
#include "eval/rpe.h"
#include "sim/pipeline/render_dataset.h"
#include "sim/scenario/scenario_loader.h"
#include "sim/scenario/shipped_scenarios.h"
#include "sim/world/sensed_frame.h"
#include "sim/world/simulated_sequence.h"
#include "slam/io/rgbd_sequence.h"
#include "slam/track/tracking_state.h"
#include "tools/bag/bag_export.h"
#include "tools/harness/plan/run_record.h"
#include "tools/harness/plan/sweep_plan.h"
#include "tools/runner/slam_runner.h"

namespace py = pybind11;
namespace fs = std::filesystem;

namespace depot::python {
namespace {

// ---- arrays ---------------------------------------------------------------

py::array_t<uint8_t> rgb_array(const cv::Mat& bgr) {
  py::array_t<uint8_t> out({bgr.rows, bgr.cols, 3});
  cv::Mat view(bgr.rows, bgr.cols, CV_8UC3, out.mutable_data());
  cv::cvtColor(bgr, view, cv::COLOR_BGR2RGB);
  return out;
}

template <typename T>
py::array_t<T> plane_array(const cv::Mat& m) {
  py::array_t<T> out({m.rows, m.cols});
  cv::Mat view(m.rows, m.cols, m.type(), out.mutable_data());
  m.copyTo(view);
  return out;
}

py::array_t<double> pose_array(const Pose& p) {
  py::array_t<double> out({4, 4});
  auto a = out.mutable_unchecked<2>();
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) a(r, c) = p.matrix()(r, c);
  return out;
}

std::string shape_text(const py::array& a) {
  std::string s = "(";
  for (py::ssize_t i = 0; i < a.ndim(); ++i) s += (i ? ", " : "") + std::to_string(a.shape(i));
  return s + (a.ndim() == 1 ? ",)" : ")");
}

// An RGB image H x W x 3 uint8 as the BGR matrix the SLAM takes.
cv::Mat bgr_from(const py::array& a) {
  if (!py::isinstance<py::array_t<uint8_t>>(a) || a.ndim() != 3 || a.shape(2) != 3)
    fail("rgb", "must be an H x W x 3 uint8 array, got " + std::string(py::str(a.dtype())) + " " +
                    shape_text(a));
  const auto c = py::array_t<uint8_t, py::array::c_style | py::array::forcecast>::ensure(a);
  const cv::Mat rgb(static_cast<int>(a.shape(0)), static_cast<int>(a.shape(1)), CV_8UC3,
                    const_cast<uint8_t*>(c.data()));
  cv::Mat bgr;
  cv::cvtColor(rgb, bgr, cv::COLOR_RGB2BGR);
  return bgr;
}

// Depth H x W float32 metres.
cv::Mat depth_from(const py::array& a, const cv::Size& size) {
  if (!py::isinstance<py::array_t<float>>(a) || a.ndim() != 2)
    fail("depth", "must be an H x W float32 array of metres, got " +
                      std::string(py::str(a.dtype())) + " " + shape_text(a));
  if (a.shape(0) != size.height || a.shape(1) != size.width)
    fail("depth", "is " + shape_text(a) + " but rgb is (" + std::to_string(size.height) + ", " +
                      std::to_string(size.width) + ")");
  const auto c = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(a);
  return cv::Mat(size, CV_32F, const_cast<float*>(c.data())).clone();
}

// ---- rendering --------------------------------------------------------------

// A scenario with the keyword arguments render() and Simulation share, as
// `depot sim render` applies its options.
struct ScenarioChoice {
  sim::Scenario scenario;
  sim::RenderRequest request;
};
ScenarioChoice choose_scenario(const std::string& name, std::optional<int> frames,
                               std::optional<uint64_t> seed, std::optional<int> width,
                               std::optional<double> load, bool ideal,
                               const std::map<std::string, std::string>& set) {
  std::vector<YamlOverride> overrides;
  for (const auto& [key, value] : set)
    overrides.push_back(parse_yaml_override(key + "=" + value, "set"));
  ScenarioChoice c{sim::load_scenario(sim::resolve_scenario(name), overrides), {}};
  c.request.frames = frames;
  c.request.seed = seed;
  c.request.width = width;
  c.request.dynamic_load = load;
  c.request.ideal = ideal;
  return c;
}

py::dict render(const std::string& scenario, const std::string& output, std::optional<int> frames,
                std::optional<uint64_t> seed, std::optional<int> width, std::optional<double> load,
                bool ideal, bool overwrite, const std::map<std::string, std::string>& set,
                bool progress) {
  sim::RenderSummary s;
  {
    py::gil_scoped_release release;
    ScenarioChoice c = choose_scenario(scenario, frames, seed, width, load, ideal, set);
    c.request.dataset.output = output;
    c.request.dataset.overwrite = overwrite;
    c.request.progress = progress;
    s = sim::render_dataset(c.scenario, c.request);
  }
  py::dict d;
  d["frames"] = s.frames;
  d["seconds"] = s.seconds;
  d["output"] = s.output;
  d["bytes"] = s.bytes;
  return d;
}

// A scenario stepped in memory: each frame as the dataset writer would
// sense it (sim/world/sensed_frame.h), before PNG quantisation.
class Simulation {
 public:
  Simulation(const std::string& scenario, std::optional<int> frames, std::optional<uint64_t> seed,
             std::optional<int> width, std::optional<double> load, bool ideal,
             const std::map<std::string, std::string>& set) {
    py::gil_scoped_release release;
    ScenarioChoice c = choose_scenario(scenario, frames, seed, width, load, ideal, set);
    sim::Scenario& sc = c.scenario;
    sim::apply_overrides(sc, c.request);
    sequence_ = std::make_unique<sim::SimulatedSequence>(sc, sim::GlBackend::kOsMesa);
  }
  int frames() const { return sequence_->frame_count(); }
  py::object step() {
    sim::RenderedFrame f;
    sim::FrameTruth t;
    cv::Mat depth;
    {
      py::gil_scoped_release release;
      MutexLock lock(mutex_);
      if (!sequence_->next(f, t)) return py::none();
      const sim::Scenario& sc = sequence_->scenario();
      depth = sim::sense_frame(f, sc, t.capture, t.covered, sim::sensor_seed(sc, t.index));
    }
    py::dict d;
    d["index"] = t.index;
    d["timestamp"] = t.rgb_timestamp;
    d["depth_timestamp"] = t.depth_timestamp;
    d["rgb"] = rgb_array(f.bgr);
    d["depth"] = plane_array<float>(depth);
    d["labels"] = plane_array<uint16_t>(f.instance);
    d["pose"] = pose_array(t.camera);
    d["covered"] = t.covered;
    py::list objects;
    for (const sim::ObjectState& o : t.objects) {
      py::dict od;
      od["id"] = o.id;
      od["pose"] = pose_array(o.pose);
      od["moving"] = o.moving;
      objects.append(od);
    }
    d["objects"] = objects;
    return d;
  }
  py::dict camera() const {
    const sim::CameraIntrinsics& c = sequence_->scenario().camera;
    py::dict d;
    d["width"] = c.width;
    d["height"] = c.height;
    d["fx"] = c.f;
    d["fy"] = c.focal_y();
    d["cx"] = c.cx;
    d["cy"] = c.cy;
    return d;
  }

 private:
  // Steps take turns; the GL context is the constructing thread's, so step
  // from the thread that made the Simulation.
  Mutex mutex_;
  std::unique_ptr<sim::SimulatedSequence> sequence_;
};

// ---- sequences --------------------------------------------------------------

class Sequence {
 public:
  Sequence(const std::string& path, const std::string& colour_topic, const std::string& depth_topic,
           const std::string& camera_info_topic)
      : path_(path) {
    seq_ = slam::open_sequence(path, {colour_topic, depth_topic, camera_info_topic});
    if (!seq_->calibration_path().empty())
      seq_->set_depth_factor(dataset::read_calibration(seq_->calibration_path()).depth_factor);
    // A simulated folder's truth: poses, labels and boxes by frame.
    std::error_code ec;
    if (fs::is_directory(path, ec)) {
      const std::string gt = (fs::path(path) / "groundtruth.txt").string();
      if (fs::is_regular_file(gt, ec))
        for (const StampedPose& p : read_tum_trajectory(gt)) truth_[key(p.timestamp)] = p.pose;
      if (dataset::has_label_list(path))
        for (const StampedFile& f : dataset::read_label_list(path))
          labels_[key(f.timestamp)] = f.path;
      if (dataset::has_boxes(path))
        for (const dataset::BoxRecord& b : dataset::read_boxes(path))
          boxes_[key(b.timestamp)].push_back(b);
    }
  }
  size_t size() const { return seq_->size(); }
  py::dict frame(py::ssize_t i) const {
    if (i < 0) i += static_cast<py::ssize_t>(size());
    if (i < 0 || static_cast<size_t>(i) >= size())
      throw py::index_error(path_ + ": frame " + std::to_string(i) + " of " +
                            std::to_string(size()));
    cv::Mat bgr, depth;
    {
      py::gil_scoped_release release;
      MutexLock lock(mutex_);  // a bag's reader caches a chunk: one reader at a time
      seq_->load(static_cast<size_t>(i), bgr, depth);
    }
    const double t = seq_->timestamp(static_cast<size_t>(i));
    py::dict d;
    d["timestamp"] = t;
    d["rgb"] = rgb_array(bgr);
    d["depth"] = plane_array<float>(depth);
    const std::string k = key(t);
    if (const auto p = truth_.find(k); p != truth_.end()) d["pose"] = pose_array(p->second);
    if (const auto l = labels_.find(k); l != labels_.end())
      d["labels"] = plane_array<uint16_t>(dataset::read_label_image(path_, l->second));
    if (!boxes_.empty()) {
      py::list boxes;
      if (const auto b = boxes_.find(k); b != boxes_.end())
        for (const dataset::BoxRecord& r : b->second) {
          py::dict box;
          box["id"] = r.id;
          box["class"] = r.class_name;
          box["box"] = py::make_tuple(r.x1, r.y1, r.x2, r.y2);
          box["visible_pixels"] = r.visible_pixels;
          box["moving"] = r.moving;
          boxes.append(box);
        }
      d["boxes"] = boxes;
    }
    return d;
  }
  std::vector<double> timestamps() const {
    std::vector<double> t;
    for (size_t i = 0; i < size(); ++i) t.push_back(seq_->timestamp(i));
    return t;
  }
  const slam::RgbdSequence& sequence() const { return *seq_; }

 private:
  static std::string key(double t) { return dataset::format_timestamp(t); }
  std::string path_;
  mutable Mutex mutex_;  // Python threads may share a Sequence; loads take turns
  std::unique_ptr<slam::RgbdSequence> seq_;
  std::map<std::string, Pose> truth_;
  std::map<std::string, std::string> labels_;
  std::map<std::string, std::vector<dataset::BoxRecord>> boxes_;
};

// ---- SLAM -------------------------------------------------------------------

std::vector<std::string> states_of(const std::vector<slam::StampedFrameState>& states) {
  std::vector<std::string> out;
  for (const slam::StampedFrameState& s : states) out.push_back(slam::frame_state_name(s.state));
  return out;
}

runner::RunOptions run_options(const std::string& dataset, const std::string& mode,
                               const std::string& detector, const std::string& mapping) {
  if (mapping != "sync" && mapping != "threaded")
    fail("mapping", "'" + mapping + "' is neither sync nor threaded");
  runner::RunOptions o;
  o.input.dataset = dataset;
  o.input.sync = mapping == "sync";
  o.rejection.mode = mode;
  o.perception.detector = detector;
  o.quiet = true;
  return o;
}

// The system fed frame by frame: the settings and rejection `depot slam run`
// would use on `dataset` (its camera, its detector default).
class Slam {
 public:
  Slam(const std::string& dataset, const std::string& mode, const std::string& detector,
       const std::string& mapping)
      : options_(run_options(dataset, mode, detector, mapping)) {
    py::gil_scoped_release release;
    const auto sequence = slam::open_sequence(dataset);
    run_ = runner::prepare_run(options_, *sequence);
  }
  py::dict track(const py::array& rgb, const py::array& depth, double timestamp) {
    const cv::Mat bgr = bgr_from(rgb);
    const cv::Mat d = depth_from(depth, bgr.size());
    slam::TrackResult r;
    {
      py::gil_scoped_release release;
      MutexLock lock(mutex_);  // the system is fed by one thread at a time
      r = run_.system->track(bgr, d, timestamp);
    }
    py::dict out;
    out["state"] = slam::tracking_state_name(r.state);
    const bool posed =
        r.state == slam::TrackingState::kOk || r.state == slam::TrackingState::kRelocalized;
    out["pose"] = posed ? py::object(pose_array(r.T_wc)) : py::none();
    out["keypoints"] = r.keypoints;
    out["kept"] = r.kept;
    if (const slam::RejectionFilter* f = run_.rejection.filter.get()) {
      // Each keypoint as the filter judged it: x, y and whether it was kept.
      const auto& kps = f->last_keypoints();
      const auto& kept = f->last_keep();
      py::array_t<float> points({static_cast<py::ssize_t>(kps.size()), py::ssize_t{2}});
      py::array_t<bool> keep(static_cast<py::ssize_t>(kps.size()));
      auto p = points.mutable_unchecked<2>();
      auto k = keep.mutable_unchecked<1>();
      for (size_t i = 0; i < kps.size(); ++i) {
        p(i, 0) = kps[i].pt.x;
        p(i, 1) = kps[i].pt.y;
        k(i) = i < kept.size() && kept[i];
      }
      out["keypoint_xy"] = points;
      out["keypoint_kept"] = keep;
    }
    return out;
  }
  py::tuple trajectory() const {
    std::vector<StampedPose> poses;
    {
      py::gil_scoped_release release;
      MutexLock lock(mutex_);
      poses = run_.system->trajectory();
    }
    return stamped_arrays(poses);
  }
  std::vector<std::string> states() const {
    MutexLock lock(mutex_);
    return states_of(run_.system->frame_states());
  }
  void finish() {
    py::gil_scoped_release release;
    MutexLock lock(mutex_);
    run_.system->finish();
  }
  static py::tuple stamped_arrays(const std::vector<StampedPose>& poses) {
    py::array_t<double> t(static_cast<py::ssize_t>(poses.size()));
    py::array_t<double> m({static_cast<py::ssize_t>(poses.size()), py::ssize_t{4}, py::ssize_t{4}});
    auto tt = t.mutable_unchecked<1>();
    auto mm = m.mutable_unchecked<3>();
    for (size_t i = 0; i < poses.size(); ++i) {
      tt(i) = poses[i].timestamp;
      for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) mm(i, r, c) = poses[i].pose.matrix()(r, c);
    }
    return py::make_tuple(t, m);
  }

 private:
  runner::RunOptions options_;
  // Python threads may share a Slam with the GIL released while it tracks:
  // the system's methods take turns (it is fed by one thread, system.h).
  mutable Mutex mutex_;
  runner::PreparedRun run_;
};

py::dict slam_run(const std::string& dataset, const std::string& output, const std::string& mode,
                  const std::string& detector, const std::string& mapping) {
  runner::RunOptions o = run_options(dataset, mode, detector, mapping);
  runner::RunSummary s;
  {
    py::gil_scoped_release release;
    s = runner::run_sequence(o);
    if (!output.empty())
      write_tum_trajectory(output, s.trajectory, "depot-slam (" + mode + ") of " + dataset);
  }
  py::dict d;
  d["frames"] = s.frames;
  d["tracked"] = s.tracked;
  d["keyframes"] = s.keyframes;
  d["median_ms"] = s.median_ms;
  d["states"] = states_of(s.frame_states);
  if (s.scored) {  // a simulated dataset with a rejection mode: scored against its labels
    // As `depot slam run` prints them: precision with the points on a
    // mover's boundary left out, and with them counted as static.
    d["rejection_precision"] = s.score.precision_without_boundary();
    d["rejection_precision_boundary_static"] = s.score.precision();
    d["rejection_recall"] = s.score.recall();
  }
  const py::tuple arrays = Slam::stamped_arrays(s.trajectory);
  d["timestamps"] = arrays[0];
  d["poses"] = arrays[1];
  return d;
}

// ---- evaluation -------------------------------------------------------------

std::vector<StampedPose> poses_from(const py::object& o, const std::string& what) {
  if (py::isinstance<py::str>(o)) return ros2::read_trajectory(o.cast<std::string>());
  const py::tuple pair = o.cast<py::tuple>();
  if (pair.size() != 2) fail(what, "must be a path or (timestamps (N,), poses (N, 4, 4))");
  const auto t = pair[0].cast<py::array_t<double, py::array::c_style | py::array::forcecast>>();
  const auto m = pair[1].cast<py::array_t<double, py::array::c_style | py::array::forcecast>>();
  if (t.ndim() != 1 || m.ndim() != 3 || m.shape(0) != t.shape(0) || m.shape(1) != 4 ||
      m.shape(2) != 4)
    fail(what, "must be timestamps (N,) and poses (N, 4, 4), got " + shape_text(t) + " and " +
                   shape_text(m));
  std::vector<StampedPose> out;
  for (py::ssize_t i = 0; i < t.shape(0); ++i) {
    Pose p = Pose::Identity();
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 4; ++c) p.matrix()(r, c) = m.at(i, r, c);
    if (!p.matrix().allFinite()) fail(what, "pose " + std::to_string(i) + " is not finite");
    out.push_back({t.at(i), p});
  }
  return out;
}

py::dict ate(const py::object& reference, const py::object& estimate, double max_dt) {
  const std::vector<StampedPose> ref = poses_from(reference, "reference");
  const std::vector<StampedPose> est = poses_from(estimate, "estimate");
  AssociationOptions assoc;
  assoc.max_difference = max_dt;
  const eval::AteResult r =
      eval::compute_ate(eval::match_trajectories(ref, est, assoc, "reference", "estimate"));
  py::dict d;
  d["rmse"] = r.statistics.rmse;
  d["mean"] = r.statistics.mean;
  d["median"] = r.statistics.median;
  d["max"] = r.statistics.max;
  d["matched"] = r.statistics.count;
  d["errors"] = py::array_t<double>(static_cast<py::ssize_t>(r.errors.size()), r.errors.data());
  return d;
}

py::dict rpe(const py::object& reference, const py::object& estimate, double delta,
             const std::string& unit, double max_dt) {
  if (unit != "s" && unit != "f")
    fail("unit", "'" + unit + "' is neither s (seconds) nor f (frames)");
  AssociationOptions assoc;
  assoc.max_difference = max_dt;
  eval::PairSelection selection;
  selection.delta = delta;
  selection.unit = unit == "s" ? eval::DeltaUnit::kSeconds : eval::DeltaUnit::kFrames;
  const eval::RpeResult r = eval::compute_rpe(
      eval::match_trajectories(poses_from(reference, "reference"), poses_from(estimate, "estimate"),
                               assoc, "reference", "estimate"),
      selection);
  py::dict d;
  d["translation_rmse"] = r.translation_statistics.rmse;
  d["rotation_rmse_deg"] = r.rotation_statistics.rmse;
  d["pairs"] = r.translation_statistics.count;
  d["translation"] =
      py::array_t<double>(static_cast<py::ssize_t>(r.translation.size()), r.translation.data());
  d["rotation_deg"] =
      py::array_t<double>(static_cast<py::ssize_t>(r.rotation.size()), r.rotation.data());
  return d;
}

// ---- sweeps -----------------------------------------------------------------

// `depot sweep run` as the program runs it (its jobs are processes of the
// program); the run records as dicts (tools/harness/plan/run_record.h).
py::list sweep(const std::vector<std::string>& scenarios, const std::string& output,
               const std::map<std::string, std::vector<std::string>>& vary,
               const std::map<std::string, std::string>& set, const std::vector<std::string>& modes,
               int seeds, int frames, int width, int workers, const std::string& program) {
  std::vector<std::string> argv = {program.empty() ? DEPOT_PROGRAM : program, "sweep", "run"};
  argv.insert(argv.end(), scenarios.begin(), scenarios.end());
  argv.insert(argv.end(), {"-o", output, "-q", "--seeds", std::to_string(seeds), "--frames",
                           std::to_string(frames), "--width", std::to_string(width), "-j",
                           std::to_string(workers)});
  for (const auto& [key, levels] : vary) {
    std::string joined;
    for (const std::string& l : levels) joined += (joined.empty() ? "" : ",") + l;
    argv.insert(argv.end(), {"--vary", key + "=" + joined});
  }
  for (const auto& [key, value] : set) argv.insert(argv.end(), {"--set", key + "=" + value});
  if (!modes.empty()) {
    std::string joined;
    for (const std::string& m : modes) joined += (joined.empty() ? "" : ",") + m;
    argv.insert(argv.end(), {"--modes", joined});
  }
  const std::string log =
      (fs::temp_directory_path() / ("depot_sweep_" + std::to_string(::getpid()) + ".log")).string();
  int status = 0;
  {
    py::gil_scoped_release release;
    ChildSpec spec;
    spec.argv = argv;
    spec.log_path = log;
    const pid_t pid = start_child(spec);
    while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
  }
  std::ifstream in(log);
  std::string line, last_error;
  while (std::getline(in, line))
    if (line.rfind("depot: error: ", 0) == 0) last_error = line.substr(14);
  in.close();
  std::error_code ec;
  fs::remove(log, ec);
  if (exit_code_of(status) != 0)
    throw Error(last_error.empty()
                    ? "depot sweep run failed (exit " + std::to_string(exit_code_of(status)) + ")"
                    : last_error);
  const harness::SweepLayout layout{output};
  py::list records;
  const py::object loads = py::module_::import("json").attr("loads");
  std::vector<std::string> ids;
  for (const auto& e : fs::directory_iterator(fs::path(output) / "runs", ec))
    if (fs::is_regular_file(layout.run_record(e.path().filename().string()), ec))
      ids.push_back(e.path().filename().string());
  std::sort(ids.begin(), ids.end());
  for (const std::string& id : ids)
    records.append(loads(harness::to_json(harness::read_run_record(layout.run_record(id))).dump()));
  return records;
}

py::dict export_mcap(const std::string& dataset, const std::string& output,
                     const std::string& compression) {
  bag::BagExportOptions options;
  options.compression = mcap::parse_compression(compression, "compression");
  options.progress = false;
  bag::BagExportReport r;
  {
    py::gil_scoped_release release;
    r = bag::export_bag(dataset, output, options);
  }
  py::dict d;
  d["frames"] = r.frames;
  d["messages"] = r.totals.messages;
  d["bytes"] = r.totals.file_bytes;
  d["topics"] = r.topics;
  return d;
}

}  // namespace
}  // namespace depot::python

PYBIND11_MODULE(depot, m) {
  using namespace depot::python;
  m.doc() = "depot-slam: the depot simulator, the dynamic-scene RGB-D SLAM and its evaluation";
  py::register_exception<depot::Error>(m, "Error", PyExc_RuntimeError);
  m.def("render", &render, py::arg("scenario"), py::arg("output"), py::arg("frames") = py::none(),
        py::arg("seed") = py::none(), py::arg("width") = py::none(), py::arg("load") = py::none(),
        py::arg("ideal") = false, py::arg("overwrite") = false,
        py::arg("set") = std::map<std::string, std::string>{}, py::arg("progress") = false,
        "Render a scenario (shipped name or YAML path) to a dataset folder; returns a summary.");
  py::class_<Simulation>(m, "Simulation", "A scenario stepped frame by frame in memory")
      .def(py::init<const std::string&, std::optional<int>, std::optional<uint64_t>,
                    std::optional<int>, std::optional<double>, bool,
                    const std::map<std::string, std::string>&>(),
           py::arg("scenario"), py::arg("frames") = py::none(), py::arg("seed") = py::none(),
           py::arg("width") = py::none(), py::arg("load") = py::none(), py::arg("ideal") = false,
           py::arg("set") = std::map<std::string, std::string>{})
      .def_property_readonly("frames", &Simulation::frames)
      .def_property_readonly("camera", &Simulation::camera)
      .def("step", &Simulation::step,
           "The next frame (rgb, depth float32 m as sensed, labels uint16, pose (4,4), "
           "objects with poses and moving flags, timestamps), or None after the last");
  py::class_<Sequence>(m, "Sequence", "A TUM folder or a ROS 2 bag, frame by frame as arrays")
      .def(py::init<const std::string&, const std::string&, const std::string&,
                    const std::string&>(),
           py::arg("path"), py::arg("colour_topic") = "", py::arg("depth_topic") = "",
           py::arg("camera_info_topic") = "")
      .def("__len__", &Sequence::size)
      .def("__getitem__", &Sequence::frame,
           "Frame i: rgb (H,W,3) uint8, depth (H,W) float32 m, timestamp; for a simulated "
           "dataset also pose (4,4) camera-to-world, labels (H,W) uint16 and boxes")
      .def_property_readonly("timestamps", &Sequence::timestamps);
  py::class_<Slam>(m, "Slam", "The SLAM system fed frame by frame")
      .def(py::init<const std::string&, const std::string&, const std::string&,
                    const std::string&>(),
           py::arg("dataset"), py::arg("mode") = "orb", py::arg("detector") = "",
           py::arg("mapping") = "sync",
           "Settings and rejection as `depot slam run DATASET --mode MODE` would use them")
      .def("track", &Slam::track, py::arg("rgb"), py::arg("depth"), py::arg("timestamp"),
           "Track one frame; returns state, pose (4,4) or None, keypoint counts and, with "
           "rejection, each keypoint's xy and whether it was kept")
      .def("trajectory", &Slam::trajectory, "(timestamps (N,), poses (N,4,4)) of tracked frames")
      .def("states", &Slam::states, "The state of every frame given")
      .def("finish", &Slam::finish, "Wait for mapping and loop closing to finish");
  m.def("slam_run", &slam_run, py::arg("dataset"), py::arg("output") = "", py::arg("mode") = "orb",
        py::arg("detector") = "", py::arg("mapping") = "sync",
        "`depot slam run` in this process; returns a summary with the trajectory as arrays");
  m.def("ate", &ate, py::arg("reference"), py::arg("estimate"), py::arg("max_dt") = 0.02,
        "ATE (TUM/evo): each of reference and estimate a TUM file, a bag, or (timestamps, poses)");
  m.def("rpe", &rpe, py::arg("reference"), py::arg("estimate"), py::arg("delta") = 1.0,
        py::arg("unit") = "s", py::arg("max_dt") = 0.02,
        "RPE (TUM/evo) over pairs `delta` seconds (unit s) or frames (unit f) apart");
  m.def("sweep", &sweep, py::arg("scenarios"), py::arg("output"),
        py::arg("vary") = std::map<std::string, std::vector<std::string>>{},
        py::arg("set") = std::map<std::string, std::string>{},
        py::arg("modes") = std::vector<std::string>{}, py::arg("seeds") = 3,
        py::arg("frames") = 300, py::arg("width") = 640, py::arg("workers") = 2,
        py::arg("program") = "",
        "`depot sweep run` (the program built beside this module, or `program`); returns the "
        "run records (ATE, RPE, tracked share, rejection scores per scenario, level, seed, mode)");
  m.def("export_mcap", &export_mcap, py::arg("dataset"), py::arg("output"),
        py::arg("compression") = "zstd", "Write a dataset as a ROS 2 bag (MCAP)");
}
