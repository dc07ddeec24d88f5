#include "dataset/ros2/bag_trajectory.h"

#include <algorithm>

#include "common/error.h"
#include "dataset/mcap/mcap_reader.h"
#include "dataset/ros2/bag_layout.h"
#include "dataset/ros2/messages.h"

namespace depot::ros2 {

namespace {

Pose pose_of(const Eigen::Vector3d& t, const Eigen::Quaterniond& q, const std::string& where) {
  if (!t.allFinite() || !q.coeffs().allFinite() ||
      std::abs(q.norm() - 1.0) > kQuaternionNormTolerance)
    fail(where, "pose with a non-finite value or a quaternion of norm " + std::to_string(q.norm()));
  Pose p = Pose::Identity();
  p.linear() = q.normalized().toRotationMatrix();
  p.translation() = t;
  return p;
}

}  // namespace

std::vector<StampedPose> read_bag_trajectory(const std::string& bag,
                                             const BagTrajectorySource& source) {
  mcap::Reader reader(bag);
  const std::string topic = source.topic.empty() ? kTruthPoseTopic : source.topic;
  const std::string child = source.child_frame.empty() ? kTruthCameraFrame : source.child_frame;
  const mcap::Channel* channel = reader.channel(topic);
  if (!channel) fail(bag, "no trajectory topic " + topic);
  const auto schema = reader.schemas().find(channel->schema_id);
  const std::string type = schema == reader.schemas().end() ? "" : schema->second.name;
  const bool poses =
      type == pose_stamped_type().name || type == without_msg(pose_stamped_type().name);
  const bool transforms =
      type == tf_message_type().name || type == without_msg(tf_message_type().name);
  if (!poses && !transforms)
    fail(bag, topic + ": messages are '" + type + "', not geometry_msgs/msg/PoseStamped or " +
                  "tf2_msgs/msg/TFMessage");
  std::vector<StampedPose> out;
  for (const mcap::MessageRef& ref : reader.messages()) {
    if (ref.channel_id != channel->id) continue;
    const std::string where = bag + " (" + topic + ")";
    const mcap::Message m = reader.read(ref);
    if (poses) {
      const PoseStamped p = decode_pose_stamped(m.data, where);
      out.push_back({mcap::seconds_of(nanoseconds_of(p.header.stamp)),
                     pose_of(p.position, p.orientation, where)});
    } else {
      for (const TransformStamped& t : decode_tf_message(m.data, where).transforms)
        if (t.child_frame_id == child)
          out.push_back({mcap::seconds_of(nanoseconds_of(t.header.stamp)),
                         pose_of(t.translation, t.rotation, where)});
    }
  }
  if (out.empty())
    fail(bag, topic + ": no pose" + (transforms ? " of frame " + child : std::string()));
  std::stable_sort(out.begin(), out.end(), [](const StampedPose& a, const StampedPose& b) {
    return a.timestamp < b.timestamp;
  });
  return out;
}

std::vector<StampedPose> read_trajectory(const std::string& path) {
  if (path.size() > 5 && path.compare(path.size() - 5, 5, ".mcap") == 0)
    return read_bag_trajectory(path);
  return read_tum_trajectory(path);
}

}  // namespace depot::ros2
