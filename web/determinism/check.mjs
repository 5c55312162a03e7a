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
// Exit 0: equal; 1: they differ; 2: something needed is missing or failed.
// UP_WASM=path.wasm checks that module instead of the web app's copy (its
// glue, the same name ending in .js, lies next to it).
// Build first: `cargo build --release -p up-cli` and `make web/public/wasm/up_wasm.wasm`.

import { execFileSync } from "node:child_process";
import { existsSync, readFileSync, statSync } from "node:fs";
import { dirname, extname, join, resolve } from "node:path";
import { fileURLToPath, pathToFileURL } from "node:url";

const here = dirname(fileURLToPath(import.meta.url));
const root = resolve(here, "..", "..");
const scenePath = resolve(process.argv[2] ?? join(here, "scene.toml"));
const upBinary = join(root, "target", "release", "up");
const wasmPath = resolve(process.env.UP_WASM ?? join(root, "web", "public", "wasm", "up_wasm.wasm"));
const gluePath = wasmPath.replace(/\.wasm$/, ".js");

function fail(code, message) {
  console.error(`determinism: ${message}`);
  process.exit(code);
}

for (const [path, how] of [
  [scenePath, "a scene file"],
  [upBinary, "build it: cargo build --release -p up-cli"],
  [wasmPath, "build it: make web/public/wasm/up_wasm.wasm"],
  [gluePath, "build it: make web/public/wasm/up_wasm.wasm"],
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
const glue = await import(pathToFileURL(gluePath).href);
glue.initSync({ module: readFileSync(wasmPath) });
const engine = new glue.Engine();
const call = (what, f) => {
  try {
    return f();
  } catch (e) {
    fail(2, `${what}: ${e.name}: ${e.message}`);
  }
};
const text = readFileSync(scenePath, "utf8");
call(`loading ${scenePath} in wasm`, () =>
  format === ".toml" ? engine.load_scene_toml(text) : engine.load_scene_json(text),
);
if (engine.body_count() !== native.balloons) {
  fail(1, `body counts differ: native ${native.balloons}, wasm ${engine.body_count()}`);
}
const ribbons = engine.ribbon_count();
if (typeof native.ribbons === "number" && native.ribbons !== ribbons) {
  fail(1, `ribbon counts differ: native ${native.ribbons}, wasm ${ribbons}`);
}
// The module says how many steps one call takes.
const { max_steps_per_call } = glue.constants();
for (let done = 0; done < steps; ) {
  const n = Math.min(max_steps_per_call, steps - done);
  call(`step(${n})`, () => engine.step(n));
  done += n;
}
// u64 comes back as a BigInt: print it as the CLI does (16 hex digits).
const wasmHash = BigInt.asUintN(64, engine.state_hash()).toString(16).padStart(16, "0");

const summary = `${scenePath}: ${native.balloons} balloons, ${ribbons} ribbons, ${steps} steps`;
if (wasmHash !== native.state_hash) {
  const age = (p) => statSync(p).mtime.toISOString();
  fail(
    1,
    `${summary}: state_hash differs: native ${native.state_hash}, wasm ${wasmHash}\n` +
      `  (built: up ${age(upBinary)}, up_wasm.wasm ${age(wasmPath)}; a stale build differs too: rebuild both)`,
  );
}
console.log(`determinism: ${summary}: native and wasm agree, state_hash ${wasmHash}`);
