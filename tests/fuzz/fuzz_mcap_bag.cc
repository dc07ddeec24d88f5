// libFuzzer target: ROS 2 bags (dataset/mcap/mcap_reader.h) and the CDR
// messages in them (dataset/ros2/messages.h): the file opened, every message
// read, and each decoded as the type its schema names.
//
// The seed is a small bag from our writer with CRCs left out (zero, "not
// computed"), so mutations reach the parsers rather than the CRC checks:
// DEPOT_FUZZ_WRITE_SEED=FILE fuzz_mcap_bag writes it and exits.
#include <cstddef>
#include <cstdint>
#include <string>

#include "dataset/mcap/mcap_reader.h"
#include "dataset/mcap/mcap_writer.h"
#include "dataset/ros2/messages.h"
#include "tests/fuzz/fuzz_support.h"

namespace {

using namespace depot;

void write_seed(const std::string& path) {
  mcap::WriterOptions options;
  options.compression = mcap::Compression::kNone;
  options.crcs = false;
  options.chunk_size = 256;
  mcap::Writer w(path, options);
  const ros2::MessageType& image = ros2::image_type();
  const ros2::MessageType& info = ros2::camera_info_type();
  const ros2::MessageType& tf = ros2::tf_message_type();
  const uint16_t colour = w.add_channel(w.add_schema(image.name, "ros2msg", image.definition),
                                        "/camera/color/image_raw", "cdr");
  const uint16_t camera = w.add_channel(w.add_schema(info.name, "ros2msg", info.definition),
                                        "/camera/color/camera_info", "cdr");
  const uint16_t transforms =
      w.add_channel(w.add_schema(tf.name, "ros2msg", tf.definition), "/tf", "cdr");
  for (uint64_t k = 0; k < 3; ++k) {
    ros2::Image im;
    im.header.stamp = {1, static_cast<uint32_t>(k)};
    im.width = 4;
    im.height = 2;
    im.encoding = "rgb8";
    im.step = 12;
    im.data = std::string(24, static_cast<char>(k));
    w.write(colour, k, k, ros2::encode(im));
    ros2::CameraInfo ci;
    ci.width = 4;
    ci.height = 2;
    ci.d = {0.1, 0, 0, 0, 0};
    w.write(camera, k, k, ros2::encode(ci));
    ros2::TFMessage m;
    m.transforms.resize(1);
    m.transforms[0].child_frame_id = "c";
    w.write(transforms, k, k, ros2::encode(m));
  }
  w.close();
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  depot::fuzz::write_seed_if_asked(write_seed);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = depot::fuzz::write_input("bag.mcap", data, size);
  depot::fuzz::expect_clean(path, [&] {
    mcap::Reader reader(path);
    for (const mcap::MessageRef& ref : reader.messages()) {
      const mcap::Message m = reader.read(ref);
      const auto channel = reader.channels().find(m.channel_id);
      if (channel == reader.channels().end()) continue;
      const auto schema = reader.schemas().find(channel->second.schema_id);
      if (schema == reader.schemas().end()) continue;
      const std::string where = path + " (" + channel->second.topic + ")";
      if (schema->second.name == ros2::image_type().name) ros2::decode_image(m.data, where);
      if (schema->second.name == ros2::camera_info_type().name)
        ros2::decode_camera_info(m.data, where);
      if (schema->second.name == ros2::tf_message_type().name)
        ros2::decode_tf_message(m.data, where);
    }
  });
  return 0;
}
