// Independent readers for the bags depot writes, run by tests/mcap_bag_test.cc:
// the MCAP library and ROS 2 CDR decoder the Foxglove/ROS tools use, from
// the npm registry (pinned in package-lock.json), never our own code.
//
//   node check_bag.mjs describe BAG   every message decoded, one JSON line
//                                     each (images by size and CRC-32 of
//                                     their bytes), after both readers
//                                     (indexed and streamed, CRCs checked)
//                                     read the whole file
//   node check_bag.mjs write BAG      a small RGB-D bag written by
//                                     @mcap/core, for our reader to read
import { open, readFile } from "node:fs/promises";
import { crc32 } from "@foxglove/crc";
import { parse } from "@foxglove/rosmsg";
import { MessageReader, MessageWriter } from "@foxglove/rosmsg2-serialization";
import { McapIndexedReader, McapStreamReader, McapWriter } from "@mcap/core";
import { FileHandleReadable, FileHandleWritable } from "@mcap/nodejs";
import { loadDecompressHandlers } from "@mcap/support";

const [mode, path] = process.argv.slice(2);
const json = (v) =>
  JSON.stringify(v, (_, x) =>
    typeof x === "bigint" ? x.toString() : x instanceof Float64Array ? Array.from(x) : x);

function summarise(topic, schema, m) {
  if (schema === "sensor_msgs/msg/Image") {
    const { data, ...rest } = m;
    return { ...rest, bytes: data.length, crc: crc32(data) };
  }
  return m;
}

async function describe() {
  const decompressHandlers = await loadDecompressHandlers();
  // 1. The whole file streamed, every chunk CRC checked, records counted.
  const stream = new McapStreamReader({ decompressHandlers, validateCrcs: true });
  stream.append(await readFile(path));
  const counts = {};
  let record;
  while ((record = stream.nextRecord())) counts[record.type] = (counts[record.type] ?? 0) + 1;
  if (!stream.done()) throw new Error(`${path}: the stream reader did not reach the end`);
  // 2. Through the summary and indexes, CRCs checked, every message decoded
  //    with the definitions stored in the file.
  const handle = await open(path, "r");
  const reader = await McapIndexedReader.Initialize({
    readable: new FileHandleReadable(handle),
    decompressHandlers,
  });
  // The data section's CRC: magic, header and every record before Data End.
  const bytes = await readFile(path);
  const dataEnd = Number(reader.footer.summaryStart) - 13;
  const dataCrc = crc32(bytes.subarray(0, dataEnd));
  if (reader.dataSectionCrc !== undefined && reader.dataSectionCrc !== dataCrc)
    throw new Error(`${path}: data section CRC ${reader.dataSectionCrc} != ${dataCrc}`);
  const decoders = new Map();
  for (const [id, channel] of reader.channelsById) {
    const schema = reader.schemasById.get(channel.schemaId);
    if (schema.encoding !== "ros2msg" || channel.messageEncoding !== "cdr")
      throw new Error(`${channel.topic}: ${schema.encoding}/${channel.messageEncoding}`);
    const definition = new TextDecoder().decode(schema.data);
    decoders.set(id, { schema: schema.name, reader: new MessageReader(parse(definition, { ros2: true })) });
  }
  console.log(json({ kind: "file", profile: reader.header.profile, library: reader.header.library,
                     records: counts, chunks: reader.chunkIndexes.length,
                     statistics: reader.statistics, dataSectionCrc: reader.dataSectionCrc ?? 0 }));
  for await (const message of reader.readMessages({ validateCrcs: true })) {
    const { schema, reader: r } = decoders.get(message.channelId);
    const topic = reader.channelsById.get(message.channelId).topic;
    const decoded = r.readMessage(message.data);
    console.log(json({ kind: "message", topic, schema, logTime: message.logTime,
                       sequence: message.sequence, message: summarise(topic, schema, decoded) }));
  }
  await handle.close();
}

// A bag as another tool writes it: bgr8 colour, 16UC1 millimetre depth
// 5 ms after it, camera_info, no summary of our making.
async function write() {
  const definitions = {
    image: "std_msgs/Header header\nuint32 height\nuint32 width\nstring encoding\nuint8 is_bigendian\nuint32 step\nuint8[] data\n" +
      "================================================================================\nMSG: std_msgs/Header\nbuiltin_interfaces/Time stamp\nstring frame_id\n" +
      "================================================================================\nMSG: builtin_interfaces/Time\nint32 sec\nuint32 nanosec\n",
    info: "std_msgs/Header header\nuint32 height\nuint32 width\nstring distortion_model\nfloat64[] d\nfloat64[9] k\nfloat64[9] r\nfloat64[12] p\nuint32 binning_x\nuint32 binning_y\nsensor_msgs/RegionOfInterest roi\n" +
      "================================================================================\nMSG: std_msgs/Header\nbuiltin_interfaces/Time stamp\nstring frame_id\n" +
      "================================================================================\nMSG: builtin_interfaces/Time\nint32 sec\nuint32 nanosec\n" +
      "================================================================================\nMSG: sensor_msgs/RegionOfInterest\nuint32 x_offset\nuint32 y_offset\nuint32 height\nuint32 width\nbool do_rectify\n",
  };
  const handle = await open(path, "w");
  const writer = new McapWriter({ writable: new FileHandleWritable(handle), chunkSize: 64 * 1024 });
  await writer.start({ profile: "ros2", library: "@mcap/core (depot test)" });
  const schema = async (name, text) =>
    ({ id: await writer.registerSchema({ name, encoding: "ros2msg", data: new TextEncoder().encode(text) }),
       codec: new MessageWriter(parse(text, { ros2: true })) });
  const image = await schema("sensor_msgs/msg/Image", definitions.image);
  const info = await schema("sensor_msgs/msg/CameraInfo", definitions.info);
  const channel = async (topic, s) =>
    writer.registerChannel({ topic, schemaId: s.id, messageEncoding: "cdr", metadata: new Map() });
  const colour = await channel("/cam/rgb", image);
  const depth = await channel("/cam/depth", image);
  const camInfo = await channel("/cam/rgb_info", info);
  const W = 40, H = 32;
  for (let f = 0; f < 3; ++f) {
    const sec = 100 + f, nanosec = 250000000;
    const header = { stamp: { sec, nanosec }, frame_id: "cam" };
    const rgb = new Uint8Array(W * H * 3).map((_, i) => (i * 7 + f) % 256);
    const mm = new Uint16Array(W * H).map((_, i) => 500 + 10 * i + f);
    const put = async (ch, codec, msg, ns) =>
      writer.addMessage({ channelId: ch, sequence: f, logTime: ns, publishTime: ns, data: codec.writeMessage(msg) });
    const ns = BigInt(sec) * 1000000000n + BigInt(nanosec);
    await put(colour, image.codec, { header, height: H, width: W, encoding: "bgr8", is_bigendian: 0, step: W * 3, data: rgb }, ns);
    await put(depth, image.codec, { header: { stamp: { sec, nanosec: nanosec + 5000000 }, frame_id: "cam" },
      height: H, width: W, encoding: "16UC1", is_bigendian: 0, step: W * 2, data: new Uint8Array(mm.buffer) }, ns + 5000000n);
    await put(camInfo, info.codec, { header, height: H, width: W, distortion_model: "plumb_bob",
      d: [0.01, 0, 0, 0, 0], k: [5, 0, 4, 0, 6, 3, 0, 0, 1], r: [1, 0, 0, 0, 1, 0, 0, 0, 1],
      p: [5, 0, 4, 0, 0, 6, 3, 0, 0, 0, 1, 0], binning_x: 0, binning_y: 0,
      roi: { x_offset: 0, y_offset: 0, height: 0, width: 0, do_rectify: false } }, ns);
  }
  await writer.end();
  await handle.close();
}

try {
  if (mode === "describe") await describe();
  else if (mode === "write") await write();
  else throw new Error("usage: node check_bag.mjs describe|write BAG");
} catch (e) {
  console.error(`check_bag: ${e.message}`);
  process.exit(1);
}
