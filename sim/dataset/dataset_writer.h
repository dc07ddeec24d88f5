#pragma once
// Writes a simulated sequence as a standard TUM RGB-D folder plus labels:
//   rgb/ depth/ rgb.txt depth.txt associations.txt groundtruth.txt
//   calibration.yaml, labels/ labels.txt objects.json object_poses.txt
//   boxes.txt boxes_yolo/ classes.txt info.json [yolo/]
// Image encoding runs on writer threads; the folder appears only when
// complete (StagedDirectory).
//
// Threads: add() and finish() run on the caller's thread, which alone owns
// the text tables; the writer threads take jobs from the queue. mutex_
// guards the queue, the closing flag, the first worker error and the
// totals (annotated for clang's analysis, common/mutex.h).
#include <condition_variable>
#include <deque>
#include <exception>
#include <functional>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "common/mutex.h"
#include "common/staged_directory.h"
#include "dataset/boxes.h"
#include "dataset/exposures.h"
#include "dataset/object_poses.h"
#include "sim/render/rendered_frame.h"
#include "sim/scenario/class_table.h"
#include "sim/scenario/scenario.h"
#include "sim/scene/scene_model.h"
#include "sim/world/simulated_sequence.h"

namespace depot::sim {

// The simulator's output folders (datasets, and ground-truth-only exports):
// recognised by info.json and these entries, so --overwrite replaces only them.
const OutputKind& simulator_output_kind();

struct DatasetOptions {
  std::string output;
  bool overwrite = false;
  bool yolo_export = false;
  int writer_threads = 2;
  // zlib level for all images; -1 = fast default: colour stored (level 0:
  // noisy colour only shrinks 1.7x at 8x the cost), depth and labels level 1.
  int png_compression = -1;
  int min_box_pixels = 30;
};

struct WriterTimings {
  double sensor_ms = 0;  // summed over frames
  double encode_write_ms = 0;
  size_t bytes = 0;
};

class DatasetWriter {
 public:
  DatasetWriter(const DatasetOptions& options, const Scenario& scenario, const ClassTable& classes,
                const std::vector<Instance>& instances);
  ~DatasetWriter();

  // Queues one frame (blocks while the queue is full).
  void add(RenderedFrame frame, const FrameTruth& truth);
  // Waits for the writers, writes the text files, and moves the folder into place.
  WriterTimings finish();

 private:
  struct Job {
    RenderedFrame frame;
    double rgb_timestamp = 0;
    std::string stamp_rgb, stamp_depth;
    int index = 0;
    bool covered = false;  // a covered camera's frame gets no sensor noise
    ColourCapture capture;
  };
  void worker();
  void write_job(Job& job, WriterTimings& timings);
  void rethrow_worker_error();
  void write_text_files();

  DatasetOptions options_;
  const Scenario& scenario_;
  const ClassTable& classes_;
  const std::vector<Instance>& instances_;
  std::unique_ptr<StagedDirectory> dir_;

  Mutex mutex_;
  std::condition_variable cv_;
  std::deque<Job> queue_ DEPOT_GUARDED_BY(mutex_);
  bool closing_ DEPOT_GUARDED_BY(mutex_) = false;
  std::exception_ptr error_ DEPOT_GUARDED_BY(mutex_);
  std::vector<std::thread> threads_;
  WriterTimings totals_ DEPOT_GUARDED_BY(mutex_);

  std::string rgb_txt_, depth_txt_, assoc_txt_, gt_txt_;
  std::string rows_txt_;  // groundtruth_rows.txt, empty for a global shutter
  // The truth files' records, written by the dataset library at the end.
  std::vector<double> label_timestamps_;
  std::vector<dataset::ObjectPoseRecord> object_poses_;
  std::vector<dataset::ExposureRecord> exposures_;  // where the sensor forms its colour
  std::vector<dataset::BoxRecord> boxes_;
  std::vector<std::pair<std::string, std::string>> yolo_files_;  // stamp -> content
  int frames_ = 0;
  std::vector<std::pair<int, int>> covered_frames_;  // first and last index of each cover
};

}  // namespace depot::sim
