// Foxglove's own client library against ltm's bridge (issue 29 item 1): connect with
// @foxglove/ws-protocol, subscribe to the topics asked for, decode every message with
// @foxglove/omgidl-serialization from the schema the bridge advertised, and compare its bytes with
// what the recorder wrote from DDS in the same run (read with @mcap/core).
//   node foxglove_client.mjs ws://127.0.0.1:PORT /robot/odometry,/tf MIN_EACH OUT.json
//   node foxglove_client.mjs --compare OUT.json RUN.mcap
import { readFileSync, writeFileSync } from "node:fs";
// Some of these packages are CommonJS, some ES modules: their exports either way.
const load = async (name) => {
  const m = await import(name);
  return { ...(m.default ?? {}), ...m };
};
const { FoxgloveClient } = await load("@foxglove/ws-protocol");
const { parseIDL } = await load("@foxglove/omgidl-parser");
const { MessageReader } = await load("@foxglove/omgidl-serialization");
const { McapIndexedReader } = await load("@mcap/core");
const { WebSocket } = await load("ws");

const hex = (u8) => Buffer.from(u8).toString("hex");

async function listen(url, topics, minEach, out) {
  const client = new FoxgloveClient({
    ws: new WebSocket(url, [FoxgloveClient.SUPPORTED_SUBPROTOCOL]),
  });
  const subs = new Map();
  const seen = Object.fromEntries(topics.map((t) => [t, []]));
  let serverInfo = null;
  const done = (code, why) => {
    writeFileSync(out, JSON.stringify({ serverInfo, seen, why }));
    client.close();
    process.exit(code);
  };
  setTimeout(() => done(1, "timed out: " + topics.map((t) => `${t} ${seen[t].length}`).join(", ")), 60000);
  client.on("error", (e) => done(1, "client error: " + e));
  client.on("serverInfo", (info) => (serverInfo = info));
  client.on("advertise", (channels) => {
    for (const ch of channels) {
      if (!topics.includes(ch.topic)) continue;
      if (ch.encoding !== "cdr" || ch.schemaEncoding !== "omgidl") done(1, `${ch.topic}: ${ch.encoding}/${ch.schemaEncoding}`);
      const reader = new MessageReader(ch.schemaName, parseIDL(ch.schema));
      subs.set(client.subscribe(ch.id), { topic: ch.topic, reader });
    }
  });
  client.on("message", ({ subscriptionId, data }) => {
    const s = subs.get(subscriptionId);
    if (!s) return;
    const bytes = new Uint8Array(data.buffer, data.byteOffset, data.byteLength);
    const msg = s.reader.readMessage(bytes);
    seen[s.topic].push({ bytes: hex(bytes), msg });
    if (topics.every((t) => seen[t].length >= minEach)) done(0, "");
  });
}

async function compare(out, mcapFile) {
  const { seen } = JSON.parse(readFileSync(out, "utf8"));
  const file = readFileSync(mcapFile);
  const readable = {
    size: async () => BigInt(file.length),
    read: async (offset, length) => file.subarray(Number(offset), Number(offset + length)),
  };
  const reader = await McapIndexedReader.Initialize({ readable });
  const recorded = new Map();
  for await (const m of reader.readMessages()) {
    const topic = reader.channelsById.get(m.channelId).topic.replace(/^rt/, "");
    if (!recorded.has(topic)) recorded.set(topic, new Set());
    recorded.get(topic).add(hex(m.data));
  }
  let problems = 0;
  for (const [topic, list] of Object.entries(seen)) {
    const r = recorded.get(topic) ?? new Set();
    const same = list.filter((x) => r.has(x.bytes)).length;
    console.log(`${topic}: ${list.length} received over WebSocket, ${same} byte for byte as recorded from DDS (${r.size} recorded)`);
    if (same !== list.length || list.length === 0) problems++;
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
        if (!frames.includes("odom->base_link")) {
          console.log(`  a tf without odom->base_link: ${frames}`);
          problems++;
        }
      }
    }
  }
  process.exit(problems === 0 ? 0 : 1);
}

const args = process.argv.slice(2);
if (args[0] === "--compare") await compare(args[1], args[2]);
else await listen(args[0], args[1].split(","), Number(args[2]), args[3]);
