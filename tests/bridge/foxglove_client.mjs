// Foxglove's own client library against ltm's bridge (issue 29 item 1): connect with
// @foxglove/ws-protocol, subscribe to the topics asked for, decode every message from the schema
// the bridge advertised (ros2msg with @foxglove/rosmsg + @foxglove/rosmsg2-serialization, omgidl
// with @foxglove/omgidl-serialization), and compare its bytes with what the recorder wrote from
// DDS in the same run (read with @mcap/core); the recorder's omgidl schema decodes the same bytes
// to the same message (the ros2msg schema matches the IDL).
//   node foxglove_client.mjs ws://127.0.0.1:PORT /robot/odometry:10,/tf:10,/robot/map_cloud:1 OUT.json
//   node foxglove_client.mjs --compare OUT.json RUN.mcap
//   node foxglove_client.mjs --all ws://127.0.0.1:PORT OUT.json   (./ltm bench bridge: every
//     channel subscribed, messages and bytes counted, not decoded, until the server closes)
import { readFileSync, writeFileSync } from "node:fs";
import { isDeepStrictEqual } from "node:util";
// Some of these packages are CommonJS, some ES modules: their exports either way.
const load = async (name) => {
  const m = await import(name);
  return { ...(m.default ?? {}), ...m };
};
const { FoxgloveClient } = await load("@foxglove/ws-protocol");
const { parseIDL } = await load("@foxglove/omgidl-parser");
const { MessageReader: IdlReader } = await load("@foxglove/omgidl-serialization");
const { parse: parseRosMsg } = await load("@foxglove/rosmsg");
const { MessageReader: Ros2Reader } = await load("@foxglove/rosmsg2-serialization");
const { McapIndexedReader } = await load("@mcap/core");
const { WebSocket } = await load("ws");

const hex = (u8) => Buffer.from(u8).toString("hex");
// Typed arrays and bigints as plain JSON values.
const plain = (v) => JSON.parse(JSON.stringify(v, (k, x) => (typeof x === "bigint" ? Number(x) : ArrayBuffer.isView(x) ? Array.from(x) : x)));

function readerFor(ch) {
  if (ch.encoding !== "cdr") throw new Error(`${ch.topic}: encoding ${ch.encoding}`);
  if (ch.schemaEncoding === "ros2msg") return new Ros2Reader(parseRosMsg(ch.schema, { ros2: true }));
  if (ch.schemaEncoding === "omgidl") return new IdlReader(ch.schemaName, parseIDL(ch.schema));
  throw new Error(`${ch.topic}: schema encoding ${ch.schemaEncoding}`);
}

// Scene topics: decoded and checked here (their messages are made by the bridge, not on DDS).
function checkScene(topic, msg, problems) {
  if (topic.endsWith("map_cloud")) {
    const finite = [];
    const view = new DataView(msg.data.buffer, msg.data.byteOffset, msg.data.byteLength);
    for (let i = 0; i < msg.width * 3; i++) finite.push(Number.isFinite(view.getFloat32(4 * i, true)));
    if (msg.width < 1 || msg.width > 5000 || msg.data.length !== 12 * msg.width || msg.point_step !== 12 ||
        msg.fields.map((f) => f.name).join() !== "x,y,z" || !["map", "odom"].includes(msg.header.frame_id) || !finite.every(Boolean))
      problems.push(`map_cloud: ${msg.width} points, ${msg.data.length} B, frame ${msg.header.frame_id}`);
    return `${msg.width} points in ${msg.header.frame_id}`;
  }
  if (topic.endsWith("mesh_scene")) {
    for (const e of msg.entities) {
      const t = e.triangles[0];
      if (e.frame_id !== "map" || !e.id.startsWith("mesh/") || !t || t.indices.length % 3 !== 0 || t.indices.length === 0 ||
          Math.max(...t.indices) >= t.points.length)
        problems.push(`mesh_scene: entity ${e.id} in ${e.frame_id}: ${t?.points.length} points, ${t?.indices.length} indices`);
    }
    return `${msg.entities.length} entities (${msg.entities.map((e) => `${e.id}: ${e.triangles[0].indices.length / 3} triangles`).join(", ")}), ${msg.deletions.length} deletions`;
  }
  return null;
}

async function listen(url, wanted, out) {
  const topics = Object.keys(wanted);
  const client = new FoxgloveClient({
    ws: new WebSocket(url, [FoxgloveClient.SUPPORTED_SUBPROTOCOL]),
  });
  const subs = new Map();
  const seen = Object.fromEntries(topics.map((t) => [t, []]));
  const channels = {};
  const problems = [];
  let serverInfo = null;
  const done = (code, why) => {
    writeFileSync(out, JSON.stringify({ serverInfo, channels, seen, why }));
    client.close();
    process.exit(code);
  };
  setTimeout(() => done(1, "timed out: " + topics.map((t) => `${t} ${seen[t].length}`).join(", ")), 90000);
  client.on("error", (e) => done(1, "client error: " + e));
  client.on("serverInfo", (info) => (serverInfo = info));
  client.on("advertise", (list) => {
    for (const ch of list) {
      if (!topics.includes(ch.topic)) continue;
      channels[ch.topic] = { schemaName: ch.schemaName, schemaEncoding: ch.schemaEncoding };
      try {
        subs.set(client.subscribe(ch.id), { topic: ch.topic, reader: readerFor(ch) });
      } catch (e) {
        done(1, String(e));
      }
    }
  });
  client.on("message", ({ subscriptionId, data }) => {
    const s = subs.get(subscriptionId);
    if (!s) return;
    const bytes = new Uint8Array(data.buffer, data.byteOffset, data.byteLength);
    const msg = s.reader.readMessage(bytes);
    const scene = checkScene(s.topic, msg, problems);
    if (problems.length > 0) done(1, problems.join("; "));
    seen[s.topic].push(scene !== null ? { summary: scene, bytes: bytes.length } : { bytes: hex(bytes), msg: plain(msg) });
    if (topics.every((t) => seen[t].length >= wanted[t])) done(0, "");
  });
}

async function compare(out, mcapFile) {
  const { seen, channels } = JSON.parse(readFileSync(out, "utf8"));
  const file = readFileSync(mcapFile);
  const readable = {
    size: async () => BigInt(file.length),
    read: async (offset, length) => file.subarray(Number(offset), Number(offset + length)),
  };
  const reader = await McapIndexedReader.Initialize({ readable });
  const recorded = new Map();  // topic -> hex -> message decoded with the recorder's omgidl schema
  for await (const m of reader.readMessages()) {
    const ch = reader.channelsById.get(m.channelId);
    const schema = reader.schemasById.get(ch.schemaId);
    const topic = ch.topic.replace(/^rt/, "");
    if (!recorded.has(topic)) recorded.set(topic, { idl: new IdlReader(schema.name, parseIDL(new TextDecoder().decode(schema.data))), bytes: new Map() });
    const r = recorded.get(topic);
    r.bytes.set(hex(m.data), plain(r.idl.readMessage(m.data)));
  }
  let problems = 0;
  for (const [topic, list] of Object.entries(seen)) {
    if (list.length > 0 && list[0].summary !== undefined) {
      console.log(`${topic} (${channels[topic].schemaName}, ${channels[topic].schemaEncoding}): ${list.length} received; last: ${list.at(-1).summary}, ${list.at(-1).bytes} B`);
      continue;
    }
    const r = recorded.get(topic) ?? { bytes: new Map() };
    const same = list.filter((x) => r.bytes.has(x.bytes)).length;
    // The ros2msg decoding of the bytes the bridge sent, field by field as the recorder's IDL
    // decodes the bytes DDS carried.
    const alike = list.filter((x) => isDeepStrictEqual(r.bytes.get(x.bytes), x.msg)).length;
    console.log(`${topic} (${channels[topic].schemaName}, ${channels[topic].schemaEncoding}): ${list.length} received over WebSocket, ` +
      `${same} byte for byte as recorded from DDS (${r.bytes.size} recorded), ${alike} decoded as the IDL decodes them`);
    if (same !== list.length || alike !== list.length || list.length === 0) problems++;
    if (channels[topic].schemaEncoding !== "ros2msg") {
      console.log(`  ${topic}: a ROS 2 type not advertised as ros2msg`);
      problems++;
    }
    for (const { msg } of list) {
      if (topic.endsWith("odometry")) {
        const p = msg.pose.pose.position;
        if (msg.header.frame_id !== "odom" || msg.child_frame_id !== "lidar" || ![p.x, p.y, p.z].every(Number.isFinite)) {
          console.log(`  decoded wrong: ${JSON.stringify(msg.header)} ${msg.child_frame_id}`);
          problems++;
        }
      }
      if (topic.endsWith("tf")) {
        const frames = msg.transforms.map((t) => `${t.header.frame_id}->${t.child_frame_id}`);
        if (!frames.every((f) => ["map->odom", "odom->base_link"].includes(f))) {
          console.log(`  a tf with a frame pair but map->odom and odom->base_link: ${frames}`);
          problems++;
        }
      }
    }
    // Published once at the start, before the client connected: the bridge kept it.
    if (topic.endsWith("tf_static") && !list.some(({ msg }) => msg.transforms.some((t) => t.child_frame_id === "lidar"))) {
      console.log("  no base_link->lidar in tf_static");
      problems++;
    }
    if (topic.endsWith("tf") && !list.some(({ msg }) => msg.transforms.some((t) => t.child_frame_id === "base_link"))) {
      console.log("  no odom->base_link in any tf");
      problems++;
    }
  }
  process.exit(problems === 0 ? 0 : 1);
}

function everything(url, out) {
  const client = new FoxgloveClient({ ws: new WebSocket(url, [FoxgloveClient.SUPPORTED_SUBPROTOCOL]) });
  const subs = new Map();
  const counts = {};
  const latencies = {};  // ms from the message's time (its DDS source timestamp) to its arrival here
  const start = Date.now();
  const done = () => {
    for (const [topic, l] of Object.entries(latencies)) {
      l.sort((a, b) => a - b);
      const at = (q) => l[Math.min(l.length - 1, Math.floor(q * l.length))];
      Object.assign(counts[topic], { latency_p50_ms: at(0.5), latency_p99_ms: at(0.99), latency_max_ms: l[l.length - 1] });
    }
    writeFileSync(out, JSON.stringify({ seconds: (Date.now() - start) / 1000, counts }));
    process.exit(0);
  };
  client.on("advertise", (list) => {
    for (const ch of list) {
      counts[ch.topic] = { schema: ch.schemaName, encoding: ch.schemaEncoding, messages: 0, bytes: 0 };
      subs.set(client.subscribe(ch.id), ch.topic);
    }
  });
  client.on("message", ({ subscriptionId, timestamp, data }) => {
    const topic = subs.get(subscriptionId);
    const c = counts[topic];
    c.messages++;
    c.bytes += data.byteLength;
    (latencies[topic] ??= []).push(Date.now() - Number(timestamp / 1000000n));
  });
  client.on("close", done);
  client.on("error", done);
}

const args = process.argv.slice(2);
if (args[0] === "--compare") await compare(args[1], args[2]);
else if (args[0] === "--all") everything(args[1], args[2]);
else await listen(args[0], Object.fromEntries(args[1].split(",").map((t) => [t.split(":")[0], Number(t.split(":")[1] ?? 1)])), args[2]);
