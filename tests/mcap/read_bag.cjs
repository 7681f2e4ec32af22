// The independent reader of hoilcd export-mcap's bags: Foxglove's MCAP reader (@mcap/core) and its
// ROS 2 CDR decoder (@foxglove/rosmsg2-serialization on @foxglove/cdr), driven by the schemas the bag
// carries, against the dataset folder's own files.
//   node read_bag.cjs DATASET BAG
// Checks: the summary, chunk and data-section CRCs; the message count of every topic against the
// dataset; every message decoded field by field: the 16- and 8-bit images equal the PNGs to the bit,
// poses equal poses.csv to 1e-9, camera info equals the manifest's intrinsics, the person boxes and
// ids equal persons.json; no decoded message leaves bytes over. Exits 1 naming the first difference.
"use strict";
const fs = require("fs");
const path = require("path");
const zlib = require("zlib");
const { McapIndexedReader, McapStreamReader } = require("@mcap/core");
const { crc32 } = require("@foxglove/crc");
const { parse } = require("@foxglove/rosmsg");
const { MessageReader } = require("@foxglove/rosmsg2-serialization");
const zstd = require("@foxglove/wasm-zstd");

const [datasetDir, bagPath] = process.argv.slice(2);
if (!datasetDir || !bagPath) {
  console.error("usage: node read_bag.cjs DATASET BAG");
  process.exit(2);
}

function fail(message) {
  throw new Error(message);
}

function expectEqual(actual, expected, what) {
  if (actual !== expected) fail(`${what}: ${actual} (expected ${expected})`);
}

function expectNear(actual, expected, tolerance, what) {
  if (!(Math.abs(actual - expected) <= tolerance)) fail(`${what}: ${actual} (expected ${expected} within ${tolerance})`);
}

function wrapAngle(a) {
  return Math.atan2(Math.sin(a), Math.cos(a));
}

// A grey PNG (8- or 16-bit, not interlaced) as its samples, row by row.
function decodeGreyPng(file) {
  const bytes = fs.readFileSync(file);
  let offset = 8;
  let width = 0, height = 0, depth = 0;
  const idat = [];
  while (offset < bytes.length) {
    const length = bytes.readUInt32BE(offset);
    const type = bytes.toString("latin1", offset + 4, offset + 8);
    const body = bytes.subarray(offset + 8, offset + 8 + length);
    if (type === "IHDR") {
      width = body.readUInt32BE(0);
      height = body.readUInt32BE(4);
      depth = body[8];
      if (body[9] !== 0 || body[12] !== 0) fail(`${file}: not a grey, non-interlaced PNG`);
    } else if (type === "IDAT") {
      idat.push(body);
    }
    offset += 12 + length;
  }
  const raw = zlib.inflateSync(Buffer.concat(idat));
  const bpp = depth / 8, stride = width * bpp;
  const out = Buffer.alloc(stride * height);
  for (let y = 0; y < height; ++y) {
    const filter = raw[y * (stride + 1)];
    const line = raw.subarray(y * (stride + 1) + 1, (y + 1) * (stride + 1));
    for (let x = 0; x < stride; ++x) {
      const a = x >= bpp ? out[y * stride + x - bpp] : 0;
      const b = y > 0 ? out[(y - 1) * stride + x] : 0;
      const c = x >= bpp && y > 0 ? out[(y - 1) * stride + x - bpp] : 0;
      let predictor = 0;
      if (filter === 1) predictor = a;
      else if (filter === 2) predictor = b;
      else if (filter === 3) predictor = (a + b) >> 1;
      else if (filter === 4) {
        const p = a + b - c, pa = Math.abs(p - a), pb = Math.abs(p - b), pc = Math.abs(p - c);
        predictor = pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
      } else if (filter !== 0) fail(`${file}: PNG filter ${filter}`);
      out[y * stride + x] = (line[x] + predictor) & 0xff;
    }
  }
  const samples = depth === 16 ? new Uint16Array(width * height) : new Uint8Array(width * height);
  for (let i = 0; i < width * height; ++i) samples[i] = depth === 16 ? out.readUInt16BE(2 * i) : out[i];
  return { width, height, depth, samples };
}

function readPoses() {
  const lines = fs.readFileSync(path.join(datasetDir, "poses.csv"), "utf8").trim().split("\n");
  const names = lines[0].split(",");
  return lines.slice(1).map((line) => {
    const values = line.split(",").map(Number);
    return Object.fromEntries(names.map((n, i) => [n, values[i]]));
  });
}

function stampNs(stamp) {
  return BigInt(stamp.sec) * 1000000000n + BigInt(stamp.nanosec);
}

function yawOf(q) {
  return 2 * Math.atan2(q.z, q.w);
}

const frameFile = (folder, frame) => path.join(datasetDir, folder, String(frame).padStart(6, "0") + ".png");

// The checks of one decoded message of frame f on its topic.
function checkMessage(topic, m, f, ctx) {
  const pose = ctx.poses[f];
  const where = `${topic} frame ${f}`;
  const expectPixels = (folder, encoding) => {
    const png = decodeGreyPng(frameFile(folder, f));
    expectEqual(m.encoding, encoding, `${where}: encoding`);
    expectEqual(m.width, png.width, `${where}: width`);
    expectEqual(m.height, png.height, `${where}: height`);
    expectEqual(m.is_bigendian, 0, `${where}: is_bigendian`);
    expectEqual(m.step, png.width * png.depth / 8, `${where}: step`);
    const data = Buffer.from(m.data.buffer, m.data.byteOffset, m.data.byteLength);
    for (let i = 0; i < png.samples.length; ++i) {
      const value = png.depth === 16 ? data.readUInt16LE(2 * i) : data[i];
      if (value !== png.samples[i]) fail(`${where}: pixel ${i} is ${value}, the PNG's ${png.samples[i]}`);
    }
  };
  switch (topic) {
    case "/thermal/image_raw": expectPixels("radiometric", "mono16"); break;
    case "/thermal/image_mono8": expectPixels("thermal", "mono8"); break;
    case "/thermal/camera_info": {
      const k = ctx.manifest.intrinsics;
      expectEqual(m.width, k.width, `${where}: width`);
      expectEqual(m.height, k.height, `${where}: height`);
      expectEqual(m.distortion_model, "plumb_bob", `${where}: distortion_model`);
      expectEqual(m.d.length, 5, `${where}: d`);
      const K = [k.fx, 0, k.cx, 0, k.fy, k.cy, 0, 0, 1];
      K.forEach((v, i) => expectEqual(m.k[i], v, `${where}: k[${i}]`));
      expectEqual(m.header.frame_id, "thermal_camera_optical", `${where}: frame_id`);
      break;
    }
    case "/odom": {
      expectEqual(m.header.frame_id, "odom", `${where}: frame_id`);
      expectEqual(m.child_frame_id, "base_link", `${where}: child_frame_id`);
      expectNear(m.pose.pose.position.x, pose.odo_x, 1e-9, `${where}: x`);
      expectNear(m.pose.pose.position.y, pose.odo_y, 1e-9, `${where}: y`);
      expectNear(wrapAngle(yawOf(m.pose.pose.orientation) - pose.odo_theta), 0, 1e-9, `${where}: yaw`);
      if (!(m.pose.covariance[0] > 0 && m.pose.covariance[35] > 0)) fail(`${where}: covariance not positive`);
      break;
    }
    case "/tf": {
      expectEqual(m.transforms.length, 1, `${where}: transforms`);
      const t = m.transforms[0];
      expectEqual(t.header.frame_id + ">" + t.child_frame_id, "odom>base_link", `${where}: frames`);
      expectNear(t.transform.translation.x, pose.odo_x, 1e-9, `${where}: x`);
      expectNear(t.transform.translation.y, pose.odo_y, 1e-9, `${where}: y`);
      expectNear(wrapAngle(yawOf(t.transform.rotation) - pose.odo_theta), 0, 1e-9, `${where}: yaw`);
      break;
    }
    case "/ground_truth/pose": {
      expectEqual(m.header.frame_id, "map", `${where}: frame_id`);
      expectNear(m.pose.position.x, pose.x, 1e-9, `${where}: x`);
      expectNear(m.pose.position.y, pose.y, 1e-9, `${where}: y`);
      expectNear(wrapAngle(yawOf(m.pose.orientation) - pose.theta), 0, 1e-9, `${where}: yaw`);
      break;
    }
    case "/ground_truth/camera_pose": {
      expectNear(m.pose.position.x, pose.cam_x, 1e-9, `${where}: x`);
      expectNear(m.pose.position.y, pose.cam_y, 1e-9, `${where}: y`);
      expectNear(m.pose.position.z, pose.cam_z, 1e-9, `${where}: z`);
      // The optical axis (camera z) in the world: yaw and pitch of the camera (REP 103, pitch down).
      const q = m.pose.orientation;
      const zx = 2 * (q.x * q.z + q.w * q.y), zy = 2 * (q.y * q.z - q.w * q.x), zz = 1 - 2 * (q.x * q.x + q.y * q.y);
      expectNear(wrapAngle(Math.atan2(zy, zx) - pose.cam_yaw), 0, 1e-9, `${where}: camera yaw`);
      expectNear(Math.atan2(-zz, Math.hypot(zx, zy)), pose.cam_pitch, 1e-9, `${where}: camera pitch`);
      break;
    }
    case "/persons": {
      const listed = (ctx.persons.get(f) || []);
      expectEqual(m.detections.length, listed.length, `${where}: detections`);
      listed.forEach((p, i) => {
        const d = m.detections[i];
        expectEqual(d.id, String(p.id), `${where}: detection ${i} id`);
        expectEqual(d.results[0].hypothesis.class_id, "person", `${where}: class_id`);
        expectNear(d.results[0].hypothesis.score, p.visible_fraction, 1e-6, `${where}: score`);
        const [x, y, w, h] = p.box_px;
        expectNear(d.bbox.center.position.x, x + w / 2, 1e-4, `${where}: box centre x`);
        expectNear(d.bbox.center.position.y, y + h / 2, 1e-4, `${where}: box centre y`);
        expectNear(d.bbox.size_x, w, 1e-4, `${where}: box width`);
        expectNear(d.bbox.size_y, h, 1e-4, `${where}: box height`);
      });
      break;
    }
    case "/thermal/depth": expectEqual(m.encoding, "32FC1", `${where}: encoding`); break;
    case "/thermal/instance": {
      expectEqual(m.encoding, "32SC1", `${where}: encoding`);
      expectEqual(m.step, 4 * m.width, `${where}: step`);
      const labels = new Int32Array(m.data.slice().buffer);
      expectEqual(labels.length, m.width * m.height, `${where}: pixels`);
      if (labels.some((v) => v < -1)) fail(`${where}: a label below -1`);
      break;
    }
    case "/tf_static": {
      expectEqual(m.transforms.length, 2, `${where}: transforms`);
      expectEqual(m.transforms.map((t) => t.header.frame_id + ">" + t.child_frame_id).join(","),
                  "base_link>thermal_camera,thermal_camera>thermal_camera_optical", `${where}: frames`);
      break;
    }
    default: fail(`unexpected topic ${topic}`);
  }
}

// The data section's CRC (Data End) over every byte before the Data End record.
function checkDataSectionCrc(bytes, reader) {
  const dataEndStart = Number(reader.footer.summaryStart) - (1 + 8 + 4);
  expectEqual(bytes[dataEndStart], 0x0f, "Data End opcode before the summary");
  const stored = bytes.readUInt32LE(dataEndStart + 9);
  expectEqual(crc32(bytes.subarray(0, dataEndStart)), stored, "data section CRC");
}

// Every record in file order, the chunks' CRCs checked by the streaming reader.
function streamAll(bytes) {
  const stream = new McapStreamReader({ decompressHandlers: decompress, validateCrcs: true });
  stream.append(bytes);
  let records = 0;
  for (let r; (r = stream.nextRecord());) ++records;
  if (!stream.done()) fail("the streaming reader did not reach the footer");
  return records;
}

const decompress = { zstd: (buffer, size) => zstd.decompress(buffer, Number(size)) };

async function main() {
  await zstd.isLoaded;
  const bytes = fs.readFileSync(bagPath);
  const manifest = JSON.parse(fs.readFileSync(path.join(datasetDir, "manifest.json"), "utf8"));
  const poses = readPoses();
  const persons = new Map();
  const outputs = manifest.outputs || ["thermal", "radiometric", "exr", "video", "persons"];
  if (outputs.includes("persons")) {
    const doc = JSON.parse(fs.readFileSync(path.join(datasetDir, "persons.json"), "utf8"));
    for (const fr of doc.frames) persons.set(fr.frame, fr.persons);
  }
  const readable = {
    size: async () => BigInt(bytes.length),
    read: async (offset, size) => bytes.subarray(Number(offset), Number(offset + size)),
  };
  const reader = await McapIndexedReader.Initialize({ readable, decompressHandlers: decompress });  // summary CRC
  expectEqual(reader.header.profile, "ros2", "profile");
  checkDataSectionCrc(bytes, reader);
  const records = streamAll(bytes);
  const frames = manifest.frame_count;
  const expected = {
    "/tf_static": 1, "/thermal/camera_info": frames, "/odom": frames, "/tf": frames,
    "/ground_truth/pose": frames, "/ground_truth/camera_pose": frames,
  };
  if (outputs.includes("radiometric")) expected["/thermal/image_raw"] = frames;
  if (outputs.includes("thermal")) expected["/thermal/image_mono8"] = frames;
  if (outputs.includes("exr")) expected["/thermal/depth"] = expected["/thermal/instance"] = frames;
  if (outputs.includes("persons")) expected["/persons"] = frames;
  const decoders = new Map(), topicOf = new Map();
  for (const [id, channel] of reader.channelsById) {
    const schema = reader.schemasById.get(channel.schemaId);
    expectEqual(schema.encoding, "ros2msg", `${channel.topic}: schema encoding`);
    expectEqual(channel.messageEncoding, "cdr", `${channel.topic}: message encoding`);
    decoders.set(id, new MessageReader(parse(new TextDecoder().decode(schema.data), { ros2: true })));
    topicOf.set(id, channel.topic);
  }
  const counts = {};
  const timeToFrame = new Map(poses.map((p, i) => [BigInt(Math.round(p.t * 1e9)), i]));
  let decoded = 0;
  for await (const message of reader.readMessages({ validateCrcs: true })) {
    const topic = topicOf.get(message.channelId);
    counts[topic] = (counts[topic] || 0) + 1;
    const f = timeToFrame.get(message.logTime);
    if (f === undefined) fail(`${topic}: log time ${message.logTime} is no frame's time in poses.csv`);
    const decoder = decoders.get(message.channelId);
    const m = decoder.readMessage(message.data);
    if (decoder.lastReadHadTrailingBytes()) fail(`${topic} frame ${f}: bytes left over after decoding`);
    const stamp = m.header ? m.header.stamp : m.transforms[0].header.stamp;
    expectEqual(stampNs(stamp), message.logTime, `${topic} frame ${f}: header stamp`);
    checkMessage(topic, m, f, { poses, manifest, persons });
    ++decoded;
  }
  const topics = new Set([...Object.keys(expected), ...Object.keys(counts)]);
  for (const topic of [...topics].sort()) {
    expectEqual(counts[topic] || 0, expected[topic] || 0, `messages on ${topic}`);
    console.log(`${topic}: ${counts[topic]} messages`);
  }
  const stats = reader.statistics;
  expectEqual(Number(stats.messageCount), Object.values(counts).reduce((a, b) => a + b, 0), "statistics message count");
  console.log(`read ${bytes.length} bytes, ${records} records, ${reader.chunkIndexes.length} chunks; ` +
              `CRCs valid; ${decoded} messages decoded and equal to the dataset`);
}

main().catch((e) => {
  console.error(`read_bag.cjs: ${bagPath}: ${e.message}`);
  process.exit(1);
});
