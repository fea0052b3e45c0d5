// Independent reader for ltm's MCAP files, and writer of files for ltm to read, built on the
// official TypeScript MCAP library (@mcap/core). Run by independent_reader_test.sh:
//   node mcap_interop.cjs NODE_DIR read FILE EXPECTED.json   @mcap/core reads FILE (indexed and
//                                                            streamed) and compares every schema,
//                                                            channel and message with EXPECTED
//   node mcap_interop.cjs NODE_DIR write FILE OUT.json MODE  @mcap/core writes FILE (MODE: zstd,
//                                                            none or unchunked) and its manifest
//   node mcap_interop.cjs NODE_DIR compare EXPECTED.json GOT.json
"use strict";
const fs = require("fs");
const path = require("path");
const { createRequire } = require("module");

const [nodeDir, command, ...args] = process.argv.slice(2);
const req = createRequire(path.join(path.resolve(nodeDir), "package.json"));
const { McapIndexedReader, McapStreamReader, McapWriter } = req("@mcap/core");
const { FileHandleReadable, FileHandleWritable } = req("@mcap/nodejs");
const zstd = req("@foxglove/wasm-zstd");
const lz4 = req("@foxglove/wasm-lz4");

const decompressHandlers = {
  zstd: (data, size) => zstd.decompress(data, Number(size)),
  lz4: (data, size) => lz4(data, Number(size)),
};

const hex = (bytes) => Buffer.from(bytes.buffer, bytes.byteOffset, bytes.byteLength).toString("hex");
const fromHex = (text) => new Uint8Array(Buffer.from(text, "hex"));

function schemaJson(s) {
  return { id: s.id, name: s.name, encoding: s.encoding, data_hex: hex(s.data) };
}
function channelJson(c) {
  const metadata = {};
  for (const [k, v] of [...c.metadata.entries()].sort()) metadata[k] = v;
  return {
    id: c.id, schema_id: c.schemaId, topic: c.topic, message_encoding: c.messageEncoding, metadata,
  };
}
function messageJson(m, channels) {
  return {
    channel_id: m.channelId, topic: channels.get(m.channelId).topic, sequence: m.sequence,
    log_time: m.logTime.toString(), publish_time: m.publishTime.toString(), data_hex: hex(m.data),
  };
}
function normalise(manifest) {
  const byId = (a, b) => a.id - b.id;
  const metadata = (c) => Object.fromEntries(Object.entries(c.metadata).sort());
  return {
    schemas: [...manifest.schemas].sort(byId),
    channels: [...manifest.channels].sort(byId).map((c) => ({ ...c, metadata: metadata(c) })),
    messages: manifest.messages,
  };
}

// Returns "" when equal, else the first difference.
function difference(want, got, label) {
  want = normalise(want);
  got = normalise(got);
  for (const key of ["schemas", "channels"]) {
    if (JSON.stringify(want[key]) !== JSON.stringify(got[key])) {
      return `${label}: ${key} differ: want ${JSON.stringify(want[key]).slice(0, 300)} got ${JSON.stringify(got[key]).slice(0, 300)}`;
    }
  }
  if (want.messages.length !== got.messages.length) {
    return `${label}: ${got.messages.length} messages, want ${want.messages.length}`;
  }
  for (let i = 0; i < want.messages.length; ++i) {
    const w = JSON.stringify(want.messages[i]);
    const g = JSON.stringify(got.messages[i]);
    if (w !== g) return `${label}: message ${i} differs: want ${w.slice(0, 200)} got ${g.slice(0, 200)}`;
  }
  return "";
}

async function readIndexed(file) {
  const handle = await fs.promises.open(file, "r");
  try {
    const reader = await McapIndexedReader.Initialize({
      readable: new FileHandleReadable(handle), decompressHandlers,
    });
    const messages = [];
    for await (const m of reader.readMessages()) messages.push(messageJson(m, reader.channelsById));
    let previous = -1n;
    for (const m of messages) {
      if (BigInt(m.log_time) < previous) throw new Error("indexed reader: messages not in log-time order");
      previous = BigInt(m.log_time);
    }
    const stats = reader.statistics;
    if (!stats || stats.messageCount !== BigInt(messages.length)) {
      throw new Error(`indexed reader: Statistics say ${stats && stats.messageCount}, read ${messages.length}`);
    }
    if (stats.chunkCount !== reader.chunkIndexes.length) throw new Error("indexed reader: chunk count");
    return {
      schemas: [...reader.schemasById.values()].map(schemaJson),
      channels: [...reader.channelsById.values()].map(channelJson),
      messages,
      chunks: reader.chunkIndexes.length,
    };
  } finally {
    await handle.close();
  }
}

function readStreamed(file) {
  const reader = new McapStreamReader({ decompressHandlers, validateCrcs: true });
  reader.append(new Uint8Array(fs.readFileSync(file)));
  const schemas = new Map();
  const channels = new Map();
  const messages = [];
  let dataEnd = false;
  for (let r; (r = reader.nextRecord()); ) {
    if (r.type === "Schema") schemas.set(r.id, schemaJson(r));
    if (r.type === "Channel") channels.set(r.id, r);
    if (r.type === "Message") messages.push(messageJson(r, channels));
    if (r.type === "DataEnd") dataEnd = true;
  }
  if (!reader.done()) throw new Error("stream reader: file did not end with a footer and magic");
  if (!dataEnd) throw new Error("stream reader: no DataEnd record");
  // File order -> log-time order (stable), as the manifest lists them.
  messages.sort((a, b) => (BigInt(a.log_time) < BigInt(b.log_time) ? -1 : BigInt(a.log_time) > BigInt(b.log_time) ? 1 : 0));
  return { schemas: [...schemas.values()], channels: [...channels.values()].map(channelJson), messages };
}

async function read(file, expectedPath) {
  const want = JSON.parse(fs.readFileSync(expectedPath, "utf8"));
  const indexed = await readIndexed(file);
  let diff = difference(want, indexed, "McapIndexedReader");
  if (!diff) diff = difference(want, readStreamed(file), "McapStreamReader");
  if (diff) throw new Error(diff);
  console.log(`${path.basename(file)}: @mcap/core read ${indexed.messages.length} messages in ${indexed.chunks} chunks, all equal to what ltm wrote`);
}

async function write(file, manifestPath, mode) {
  const handle = await fs.promises.open(file, "w");
  const writer = new McapWriter({
    writable: new FileHandleWritable(handle),
    useChunks: mode !== "unchunked",
    chunkSize: 16 * 1024,
    compressChunk: mode === "zstd"
      ? (data) => ({ compression: "zstd", compressedData: zstd.compress(data, 3) })
      : undefined,
  });
  await writer.start({ profile: "", library: "@mcap/core interop test" });
  const idl = "module interop { struct Sample { unsigned long long stamp; sequence<octet> blob; }; };";
  const schemaId = await writer.registerSchema({
    name: "interop::Sample", encoding: "omgidl", data: new TextEncoder().encode(idl),
  });
  const topics = ["/node/a", "/node/b", "/node/c"];
  const channelIds = [];
  for (const topic of topics) {
    channelIds.push(await writer.registerChannel({
      schemaId: topic === "/node/c" ? 0 : schemaId, topic,
      messageEncoding: topic === "/node/c" ? "json" : "cdr",
      metadata: new Map(topic === "/node/a" ? [["writer", "node"], ["k", "v"]] : []),
    }));
  }
  const schemas = [{ id: schemaId, name: "interop::Sample", encoding: "omgidl", data_hex: hex(new TextEncoder().encode(idl)) }];
  const channels = topics.map((topic, i) => ({
    id: channelIds[i], schema_id: topic === "/node/c" ? 0 : schemaId, topic,
    message_encoding: topic === "/node/c" ? "json" : "cdr",
    metadata: topic === "/node/a" ? { k: "v", writer: "node" } : {},
  }));
  let seed = 12345;
  const rnd = () => (seed = (seed * 1103515245 + 12345) % 2147483648);
  const messages = [];
  const sequences = [0, 0, 0];
  for (let i = 0; i < 400; ++i) {
    const c = rnd() % 3;
    const size = i % 50 === 7 ? 0 : rnd() % 4000;
    const data = new Uint8Array(size);
    for (let k = 0; k < size; ++k) data[k] = k % 3 ? rnd() % 256 : k % 256;
    const logTime = 1600000000000000000n + BigInt(i) * 5000000n;
    messages.push({ channelId: channelIds[c], sequence: ++sequences[c], logTime, publishTime: logTime - 777n, data });
  }
  // Written out of log-time order in places; the manifest lists log-time order.
  const order = messages.map((_, i) => i);
  for (let i = 0; i + 1 < order.length; i += 9) [order[i], order[i + 1]] = [order[i + 1], order[i]];
  for (const i of order) await writer.addMessage(messages[i]);
  await writer.end();
  await handle.close();
  const channelById = new Map(channels.map((c) => [c.id, c]));
  const manifest = {
    schemas, channels,
    messages: messages.map((m) => ({
      channel_id: m.channelId, topic: channelById.get(m.channelId).topic, sequence: m.sequence,
      log_time: m.logTime.toString(), publish_time: m.publishTime.toString(), data_hex: hex(m.data),
    })),
  };
  fs.writeFileSync(manifestPath, JSON.stringify(manifest, null, 1));
  console.log(`${path.basename(file)}: @mcap/core wrote ${messages.length} messages (${mode})`);
}

function compare(wantPath, gotPath) {
  const diff = difference(JSON.parse(fs.readFileSync(wantPath, "utf8")),
    JSON.parse(fs.readFileSync(gotPath, "utf8")), `ltm reading ${path.basename(wantPath)}`);
  if (diff) throw new Error(diff);
  console.log(`${path.basename(gotPath)}: ltm read every message as @mcap/core wrote it`);
}

(async () => {
  await zstd.isLoaded;
  await lz4.isLoaded;
  if (command === "read") await read(args[0], args[1]);
  else if (command === "write") await write(args[0], args[1], args[2]);
  else if (command === "compare") compare(args[0], args[1]);
  else throw new Error(`unknown command ${command}`);
})().catch((e) => {
  console.error(`FAIL: ${e.message}`);
  process.exit(1);
});
