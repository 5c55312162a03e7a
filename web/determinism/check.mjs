#!/usr/bin/env node
// Native vs WebAssembly determinism: the same scene stepped the same number
// of times must end with the same World::state_hash in both builds.
//
//   node web/determinism/check.mjs [SCENE.toml|SCENE.json]
//
// Runs `target/release/up run SCENE --json` (native; it picks its steps as
// round(sim.duration_s / sim.dt)), then loads web/public/wasm/up_wasm.wasm in
// Node (no browser), builds the world from the same text through
// up_world_from_toml / up_world_from_json, takes exactly the native run's
// number of steps with up_step and compares up_state_hash.
// Exit 0: equal; 1: they differ; 2: something needed is missing or failed.
// UP_WASM=path.wasm checks that module instead of the web app's copy.
// Build first: `cargo build --release -p up-cli` and `make web/public/wasm/up_wasm.wasm`.

import { execFileSync } from "node:child_process";
import { existsSync, readFileSync, statSync } from "node:fs";
import { dirname, extname, join, resolve } from "node:path";
import { fileURLToPath } from "node:url";

const here = dirname(fileURLToPath(import.meta.url));
const root = resolve(here, "..", "..");
const scenePath = resolve(process.argv[2] ?? join(here, "scene.toml"));
const upBinary = join(root, "target", "release", "up");
// UP_WASM=path checks another build (e.g. target/wasm32-unknown-unknown/release/up_wasm.wasm).
const wasmPath = resolve(process.env.UP_WASM ?? join(root, "web", "public", "wasm", "up_wasm.wasm"));
/** Most steps one up_step call takes (crates/up-wasm). */
const MAX_STEPS_PER_CALL = 10_000;

function fail(code, message) {
  console.error(`determinism: ${message}`);
  process.exit(code);
}

for (const [path, how] of [
  [scenePath, "a scene file"],
  [upBinary, "build it: cargo build --release -p up-cli"],
  [wasmPath, "build it: make web/public/wasm/up_wasm.wasm"],
]) {
  if (!existsSync(path)) fail(2, `${path} is missing (${how})`);
}
const format = extname(scenePath).toLowerCase();
if (format !== ".toml" && format !== ".json") fail(2, `${scenePath}: expected a .toml or .json scene`);

// ---- native ----
let native;
try {
  const out = execFileSync(upBinary, ["run", scenePath, "--json"], { encoding: "utf8" });
  native = JSON.parse(out.trim().split("\n").pop());
} catch (e) {
  fail(2, `up run ${scenePath} failed: ${e.stderr ?? e.message}`);
}
const steps = native.steps;
if (!Number.isInteger(steps) || steps < 1) fail(2, `up run gave no step count: ${JSON.stringify(native)}`);

// ---- WebAssembly ----
const bytes = readFileSync(wasmPath);
const { instance } = await WebAssembly.instantiate(bytes, {
  env: { up_now_ms: () => performance.now() },
});
const api = instance.exports;
const decoder = new TextDecoder();
const lastError = () =>
  decoder.decode(new Uint8Array(api.memory.buffer, api.up_last_error_ptr(), api.up_last_error_len()));
const check = (status, what) => {
  if (status !== 0) fail(2, `${what}: status ${status}: ${lastError()}`);
};

const text = new TextEncoder().encode(readFileSync(scenePath, "utf8"));
const ptr = api.up_alloc(text.length);
if (ptr === 0) fail(2, `up_alloc(${text.length}): ${lastError()}`);
new Uint8Array(api.memory.buffer, ptr, text.length).set(text);
const load = format === ".toml" ? api.up_world_from_toml : api.up_world_from_json;
check(load(ptr, text.length), `loading ${scenePath} in wasm`);
check(api.up_free(ptr, text.length), "up_free");
if (api.up_body_count() !== native.balloons) {
  fail(1, `body counts differ: native ${native.balloons}, wasm ${api.up_body_count()}`);
}
for (let done = 0; done < steps; ) {
  const n = Math.min(MAX_STEPS_PER_CALL, steps - done);
  check(api.up_step(n), `up_step(${n})`);
  done += n;
}
// u64 comes back as a signed BigInt: print it as the CLI does (16 hex digits).
const wasmHash = BigInt.asUintN(64, api.up_state_hash()).toString(16).padStart(16, "0");

const summary = `${scenePath}: ${native.balloons} balloons, ${steps} steps`;
if (wasmHash !== native.state_hash) {
  const age = (p) => statSync(p).mtime.toISOString();
  fail(
    1,
    `${summary}: state_hash differs: native ${native.state_hash}, wasm ${wasmHash}\n` +
      `  (built: up ${age(upBinary)}, up_wasm.wasm ${age(wasmPath)}; a stale build differs too: rebuild both)`,
  );
}
console.log(`determinism: ${summary}: native and wasm agree, state_hash ${wasmHash}`);
