#!/usr/bin/env node
// Native vs WebAssembly determinism: the same scene stepped the same number
// of times must end with the same World::state_hash in both builds.
//
//   node web/determinism/check.mjs [SCENE.toml|SCENE.json]
//
// Runs `target/release/up run SCENE --json` (native; it picks its steps as
// round(sim.duration_s / sim.dt)), then loads web/public/wasm/up_wasm.wasm with
// its wasm-bindgen glue (up_wasm.js, `initSync`) in Node (no browser), builds
// the world from the same text with `Engine.load_scene_toml` / `load_scene_json`,
// takes exactly the native run's number of steps and compares `state_hash`.
// Its scene has ribbons, which the hash covers; the ribbon counts are
// compared too where the CLI reports them (`ribbons` in its JSON).
// `make test-determinism` runs it on scene.toml and again on fan-scene.toml,
// the same kind of room with moving air (a sweeping fan, a vent and a
// door's draught switched on and off), so that every drag against the air
// is compared too.
// Then the same with the threaded module (web/public/wasm/threads) on 1, 2
// and 4 threads (UP_CHECK_THREADS=1,2,4), each in a process of its own (a
// process holds one pool; web/sim-node/loadEngine.mjs loads it).
// Beside the end hashes, every step is compared body by body: the native run
// writes its body hash lines (`up run --body-hashes`, one a step), each wasm
// run steps one step at a time and compares its `body_hash_line()` with the
// native line of that step, so that where the builds part the check names the
// first step and body, and which of the body's fields (bodyHashes.mjs).
// Exit 0: equal; 1: they differ; 2: something needed is missing or failed.
// UP_WASM=path.wasm checks that module instead of the web app's copy (its
// glue, the same name ending in .js, lies next to it); UP_CHECK_THREADS=""
// leaves the threaded module out.
// Build first: `cargo build --release -p up-cli`, `make web/public/wasm/up_wasm.wasm`
// and `make web/public/wasm/threads/up_wasm.wasm`.

import { execFileSync, spawnSync } from "node:child_process";
import { existsSync, mkdtempSync, readFileSync, rmSync, statSync } from "node:fs";
import { tmpdir } from "node:os";
import { dirname, extname, join, resolve } from "node:path";
import { fileURLToPath, pathToFileURL } from "node:url";
import { describeParting, fieldsOf, firstParting } from "./bodyHashes.mjs";

const here = dirname(fileURLToPath(import.meta.url));
const root = resolve(here, "..", "..");
const scenePath = resolve(process.argv[2] ?? join(here, "scene.toml"));
const upBinary = join(root, "target", "release", "up");
const wasmPath = resolve(process.env.UP_WASM ?? join(root, "web", "public", "wasm", "up_wasm.wasm"));
const gluePath = wasmPath.replace(/\.wasm$/, ".js");
const threadedPath = join(root, "web", "public", "wasm", "threads", "up_wasm.wasm");
/** Thread counts the threaded module is checked on. */
const threadCounts = (process.env.UP_CHECK_THREADS ?? "1,2,4")
  .split(",")
  .filter((t) => t.trim() !== "")
  .map((t) => {
    const n = Number(t);
    if (!Number.isInteger(n) || n < 1 || n > 256) {
      console.error(`determinism: UP_CHECK_THREADS: expected integers from 1 to 256, found ${JSON.stringify(t)}`);
      process.exit(2);
    }
    return n;
  });
/** Set in the child that runs the threaded module: its thread count and steps. */
const child = process.env.UP_CHECK_CHILD ? JSON.parse(process.env.UP_CHECK_CHILD) : null;

function fail(code, message) {
  console.error(`determinism: ${message}`);
  process.exit(code);
}

for (const [path, how] of [
  [scenePath, "a scene file"],
  [upBinary, "build it: cargo build --release -p up-cli"],
  [wasmPath, "build it: make web/public/wasm/up_wasm.wasm"],
  [gluePath, "build it: make web/public/wasm/up_wasm.wasm"],
  ...(threadCounts.length > 0 ? [[threadedPath, "build it: make web/public/wasm/threads/up_wasm.wasm"]] : []),
]) {
  if (!existsSync(path)) fail(2, `${path} is missing (${how})`);
}
const format = extname(scenePath).toLowerCase();
if (format !== ".toml" && format !== ".json") fail(2, `${scenePath}: expected a .toml or .json scene`);

const text = readFileSync(scenePath, "utf8");
const call = (what, f) => {
  try {
    return f();
  } catch (e) {
    fail(2, `${what}: ${e.name}: ${e.message}`);
  }
};

/** The native run's body hash file: its field names and its lines, one a step from step 0. */
function readBodyHashes(path) {
  const [header, ...lines] = readFileSync(path, "utf8").trimEnd().split("\n");
  return { fields: fieldsOf(header), lines };
}

/**
 * The world of the scene in `glue`'s module after `steps` steps: its counts,
 * its state hash, and where it first parted from the native lines `native`
 * (readBodyHashes; compared after every step; null if it never did).
 */
function runWasm(glue, steps, native) {
  const engine = new glue.Engine();
  call(`loading ${scenePath} in wasm`, () =>
    format === ".toml" ? engine.load_scene_toml(text) : engine.load_scene_json(text),
  );
  let parting = null;
  for (let done = 0; ; done++) {
    const line = call("body_hash_line()", () => engine.body_hash_line());
    parting = firstParting(native.lines[done] ?? "(no native line)", line, native.fields);
    if (parting !== null || done === steps) break;
    call("step(1)", () => engine.step(1));
  }
  // u64 comes back as a BigInt: print it as the CLI does (16 hex digits).
  const hash = BigInt.asUintN(64, engine.state_hash()).toString(16).padStart(16, "0");
  return {
    bodies: engine.body_count(),
    ribbons: engine.ribbon_count(),
    hash,
    parting: parting && describeParting(parting),
  };
}

// ---- the threaded module, in a child process of its own ----
if (child) {
  const { loadUpWasm } = await import(pathToFileURL(join(root, "web", "sim-node", "loadEngine.mjs")).href);
  let loaded;
  try {
    loaded = await loadUpWasm({ threads: child.threads, threaded: true });
  } catch (e) {
    fail(2, `the threaded module on ${child.threads} thread(s): ${e.message}`);
  }
  const hashes = readBodyHashes(child.bodyHashes);
  console.log(JSON.stringify({ threads: loaded.threads, ...runWasm(loaded.glue, child.steps, hashes) }));
  process.exit(0);
}

// ---- native ----
let native;
const scratch = mkdtempSync(join(tmpdir(), "up-determinism-"));
process.on("exit", () => rmSync(scratch, { recursive: true, force: true }));
const bodyHashesPath = join(scratch, "body-hashes.txt");
try {
  const out = execFileSync(upBinary, ["run", scenePath, "--json", "--body-hashes", bodyHashesPath], {
    encoding: "utf8",
  });
  native = JSON.parse(out.trim().split("\n").pop());
} catch (e) {
  fail(2, `up run ${scenePath} failed: ${e.stderr ?? e.message}`);
}
const nativeHashes = call(`reading ${bodyHashesPath}`, () => readBodyHashes(bodyHashesPath));
const steps = native.steps;
if (!Number.isInteger(steps) || steps < 1) fail(2, `up run gave no step count: ${JSON.stringify(native)}`);

/** Fails unless `wasm` (runWasm's result, from `what`) ended as the native run did. */
function compare(what, wasm, built) {
  if (wasm.bodies !== native.balloons) {
    fail(1, `${what}: body counts differ: native ${native.balloons}, wasm ${wasm.bodies}`);
  }
  if (typeof native.ribbons === "number" && native.ribbons !== wasm.ribbons) {
    fail(1, `${what}: ribbon counts differ: native ${native.ribbons}, wasm ${wasm.ribbons}`);
  }
  const summary = `${scenePath}: ${native.balloons} balloons, ${wasm.ribbons} ribbons, ${steps} steps`;
  if (wasm.parting !== null || wasm.hash !== native.state_hash) {
    const age = (p) => statSync(p).mtime.toISOString();
    const how =
      wasm.parting === null
        ? `state_hash differs: native ${native.state_hash}, wasm ${wasm.hash}`
        : `native and wasm differ, ${wasm.parting}`;
    fail(
      1,
      `${summary}: ${what}: ${how}\n` +
        `  (built: up ${age(upBinary)}, ${built} ${age(built)}; a stale build differs too: rebuild both)`,
    );
  }
  console.log(`determinism: ${summary}: native and ${what} agree at every step, state_hash ${wasm.hash}`);
}

// ---- WebAssembly, one thread ----
const glue = await import(pathToFileURL(gluePath).href);
glue.initSync({ module: readFileSync(wasmPath) });
compare("wasm", runWasm(glue, steps, nativeHashes), wasmPath);

// ---- WebAssembly, threaded ----
for (const threads of threadCounts) {
  const run = spawnSync(process.execPath, [fileURLToPath(import.meta.url), scenePath], {
    encoding: "utf8",
    env: { ...process.env, UP_CHECK_CHILD: JSON.stringify({ threads, steps, bodyHashes: bodyHashesPath }) },
    timeout: 600_000,
  });
  if (run.status !== 0) fail(2, `the threaded module on ${threads} thread(s) failed (exit ${run.status ?? run.signal}): ${run.stderr.trim()}`);
  const wasm = JSON.parse(run.stdout.trim().split("\n").pop());
  if (wasm.threads !== threads) fail(2, `the threaded module ran on ${wasm.threads} thread(s), ${threads} asked for`);
  compare(`wasm on ${threads} thread(s)`, wasm, threadedPath);
}
