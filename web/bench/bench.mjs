#!/usr/bin/env node
// UP's WebAssembly build against the engines a web developer would pick
// instead, in Node, on the benchmark scene of up-bench (docs/benchmarks.md):
// @dimforge/rapier3d-compat, its SIMD build @dimforge/rapier3d-simd-compat, and
// jolt-physics (jolt.mjs). The same scene, the same interleaved timing and the
// same JSON lines as `up-bench --json`, with "runtime": "wasm-node".
//
//   node web/bench/bench.mjs --balloons 1000 [--steps K] [--threads T] [--json]
//                            [--engines up,rapier,rapier-simd,jolt]
//
// --threads T: UP and Jolt on T threads (Jolt's multithreaded flavour above 1);
// Rapier's npm builds run on one. --threaded: UP's threaded module even on one
// thread (a pool of one), to set its cost apart from the single-threaded module's.
// --thread-times: each of UP's threads in each stage (busy, at barriers, idle), as
// up-bench's table, after the run (two clock reads per task while timed). Needs target/release/up-bench (the scene,
// the peers' matched parameters, and the overlap measure — one measurement for
// every engine, natively) and UP's modules with their glue: web/public/wasm/up_wasm.wasm
// on one thread, web/public/wasm/threads/up_wasm.wasm on more (make builds both).
// Peak memory: each engine alone in a child process (`--rss-probe ENGINE`).

import { execFileSync, spawnSync } from 'node:child_process';
import { mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { performance } from 'node:perf_hooks';
import { JoltEngine, loadJolt } from './jolt.mjs';
import { loadUpWasm } from '../sim-node/loadEngine.mjs';
import { intArg } from '../scripts/cliArgs.mjs';

const HERE = dirname(fileURLToPath(import.meta.url));
const ROOT = resolve(HERE, '..', '..');
/** Rapier's poses are written in UP's layout; UpWasm.load holds this to the module's stride. */
const POSE_FLOATS = 7;
/** Removes what loading an engine left behind (Jolt's patched copy), at exit. */
const cleanups = [];

/** The engines this bench runs, by name: UP and the peers a web developer would pick instead. */
const ENGINES = ['up', 'rapier', 'rapier-simd', 'jolt'];
/** Rapier's npm builds: the plain one and the SIMD one (wasm simd128, as UP's module). */
const RAPIER_PACKAGES = { rapier: '@dimforge/rapier3d-compat', 'rapier-simd': '@dimforge/rapier3d-simd-compat' };
const PACKAGES = { ...RAPIER_PACKAGES, jolt: 'jolt-physics' };

/** A Rapier build, imported only where it runs (UP's memory probe never loads it). */
async function loadRapier(name) {
  const RAPIER = (await import(RAPIER_PACKAGES[name])).default;
  await RAPIER.init();
  return RAPIER;
}

/** The version of an installed package, as its package.json says. */
function packageVersion(name) {
  return JSON.parse(readFileSync(join(HERE, 'node_modules', ...name.split('/'), 'package.json'), 'utf8')).version;
}

function parseArgs(argv) {
  const opts = {
    balloons: 1000,
    steps: null,
    seed: 1,
    json: false,
    engines: [...ENGINES],
    threads: 1,
    threaded: false,
    rss: true,
    rssProbe: null,
    upBench: join(ROOT, 'target', 'release', 'up-bench'),
  };
  for (let i = 2; i < argv.length; i++) {
    const arg = argv[i];
    const next = () => {
      if (i + 1 >= argv.length) throw new Error(`${arg}: expected a value`);
      return argv[++i];
    };
    switch (arg) {
      case '--balloons': opts.balloons = intArg(arg, next(), 1, 50000); break;
      case '--steps': opts.steps = intArg(arg, next(), 1, 1000000); break;
      case '--threads': opts.threads = intArg(arg, next(), 1, 256); break;
      case '--threaded': opts.threaded = true; break;
      case '--thread-times': opts.threadTimes = true; break;
      case '--seed': opts.seed = intArg(arg, next(), 0, Number.MAX_SAFE_INTEGER); break;
      case '--json': opts.json = true; break;
      case '--no-rss': opts.rss = false; break;
      case '--engines':
        opts.engines = next().split(',').map((e) => e.trim());
        for (const e of opts.engines) {
          if (!ENGINES.includes(e)) throw new Error(`--engines: expected some of ${ENGINES.join(', ')}, found ${JSON.stringify(e)}`);
        }
        break;
      case '--rss-probe': opts.rssProbe = next(); break;
      case '--up-bench': opts.upBench = resolve(next()); break;
      case '--help':
        console.log(`node bench.mjs [--balloons N] [--steps K] [--seed S] [--threads T] [--threaded] [--thread-times] [--json] [--engines ${ENGINES.join(',')}] [--no-rss] [--up-bench PATH]`);
        process.exit(0);
        break;
      default: throw new Error(`unknown argument ${JSON.stringify(arg)} (try --help)`);
    }
  }
  return opts;
}

/** The scene and Rapier's matched parameters, from up-bench. */
function loadScene(opts) {
  const text = execFileSync(opts.upBench, ['--balloons', String(opts.balloons), '--seed', String(opts.seed), '--print-scene'], {
    encoding: 'utf8',
    maxBuffer: 1 << 28,
  });
  return JSON.parse(text);
}

// ---- UP, through its wasm-bindgen API (crates/up-wasm) ----

class UpWasm {
  /** Loads the module at `path` with its glue (the same name ending in .js) next to it. */
  /** One thread: today's module unless `threaded`; T threads: the threaded one on a pool of T workers (sim-node/loadEngine.mjs). */
  static async load(threads, threaded = threads > 1) {
    const { glue, memory } = await loadUpWasm({ threads, threaded });
    return new UpWasm(glue, memory);
  }

  constructor(glue, memory) {
    this.glue = glue;
    this.memory = memory;
    this.engine = new glue.Engine();
    // Strides come from the module, not from copies here.
    this.constants = glue.constants();
    if (this.constants.pose_stride !== POSE_FLOATS) {
      throw new Error(`UP's wasm writes ${this.constants.pose_stride} floats per pose, this bench compares ${POSE_FLOATS}`);
    }
  }

  loadSceneJson(json) {
    this.engine.load_scene_json(json);
  }

  step() {
    this.engine.step(1);
  }

  bodyCount() {
    return this.engine.body_count();
  }

  /** A copy of every pose (x, y, z, qx, qy, qz, qw), dense order = creation order. */
  poses() {
    const n = this.engine.write_poses();
    return new Float32Array(this.memory.buffer, this.engine.poses_ptr(), n).slice();
  }

  room() {
    const m = this.memory.buffer;
    const e = this.engine;
    return {
      vertices: new Float32Array(m, e.room_vertices_ptr(), e.room_vertices_len()).slice(),
      triangles: new Uint32Array(m, e.room_triangles_ptr(), e.room_triangles_len()).slice(),
    };
  }

  /** Leaf spheres of model 0's tree: [x, y, z, r] in the body frame. */
  leaves() {
    const stride = this.constants.tree_stride;
    const count = this.engine.write_model_tree(0);
    const nodes = new Float32Array(this.memory.buffer, this.engine.tree_ptr(), count * stride);
    const out = [];
    for (let i = 0; i < nodes.length; i += stride) {
      if (nodes[i + 5] !== 0) out.push([nodes[i], nodes[i + 1], nodes[i + 2], nodes[i + 3]]);
    }
    return out;
  }

  awakeCount() {
    return this.engine.stats().awake;
  }

  /** Times each thread's part of each stage from the next step on (or stops). */
  setThreadTiming(on) {
    this.glue.set_thread_timing(on);
  }

  /** Each stage's per-thread means a step since the last read (crates/up-wasm/src/thread_stats.rs). */
  threadTimes() {
    return this.engine.stats().threads;
  }
}

/** The per-thread figures as up-bench's `--thread-times` table (crates/up-bench/src/thread_times.rs). */
function threadTable(stages) {
  const total = stages.length ? stages[stages.length - 1].wall_ms : 0;
  const threads = stages.length ? stages[0].busy_ms.length : 0;
  const who = (t) => `${t === 0 ? "step's" : `t${t}`} busy/barrier/idle`;
  let out = `${'stage, ms/step'.padEnd(16)} ${'wall'.padStart(8)} ${'barriers'.padStart(9)} ${'passes'.padStart(7)}`;
  for (let t = 0; t < threads; t++) out += `  ${who(t).padStart(22)}`;
  out += '\n';
  for (const s of stages.filter((s) => s.stage === 'total' || s.wall_ms >= 0.01 * total)) {
    out += `${s.stage.padEnd(16)} ${s.wall_ms.toFixed(3).padStart(8)} ${s.barriers.toFixed(1).padStart(9)} ${s.passes.toFixed(1).padStart(7)}`;
    for (let t = 0; t < threads; t++) {
      out += `  ${`${s.busy_ms[t].toFixed(2)}/${s.barrier_ms[t].toFixed(2)}/${s.idle_ms[t].toFixed(2)}`.padStart(22)}`;
    }
    out += '\n';
  }
  return out;
}

class UpEngine {
  constructor(up, threads) {
    this.up = up;
    this.name = 'up';
    this.threads = threads;
  }
  step() { this.up.step(); }
  poses() { return this.up.poses(); }
  awakeCount() { return this.up.awakeCount(); }
}

// ---- Rapier, built to match (see crates/up-bench/src/rapier_engine.rs) ----

function rotate(q, v) {
  // v + 2·w·(u × v) + 2·u × (u × v), u = (qx, qy, qz).
  const tx = 2 * (q.y * v[2] - q.z * v[1]);
  const ty = 2 * (q.z * v[0] - q.x * v[2]);
  const tz = 2 * (q.x * v[1] - q.y * v[0]);
  return [
    v[0] + q.w * tx + (q.y * tz - q.z * ty),
    v[1] + q.w * ty + (q.z * tx - q.x * tz),
    v[2] + q.w * tz + (q.x * ty - q.y * tx),
  ];
}

class RapierEngine {
  /** `RAPIER`: the build `name` names (plain or SIMD). */
  constructor(RAPIER, name, setup, room, startPoses, leaves) {
    this.name = name;
    this.threads = 1;
    this.setup = setup;
    const world = new RAPIER.World({ x: 0, y: 0, z: 0 }); // weight is applied as a force
    world.timestep = setup.dt;
    const ip = world.integrationParameters;
    ip.numSolverIterations = setup.num_solver_iterations;
    ip.numInternalPgsIterations = setup.num_internal_pgs_iterations;
    ip.contact_natural_frequency = setup.contact_natural_frequency;
    ip.maxCcdSubsteps = setup.ccd ? 1 : 0;
    world.createCollider(
      RAPIER.ColliderDesc.trimesh(room.vertices, room.triangles, RAPIER.TriMeshFlags.FIX_INTERNAL_EDGES)
        .setFriction(setup.friction)
        .setRestitution(setup.restitution),
    );
    const v3 = (a) => ({ x: a[0], y: a[1], z: a[2] });
    const frame = { x: setup.inertia_frame[0], y: setup.inertia_frame[1], z: setup.inertia_frame[2], w: setup.inertia_frame[3] };
    const balls = leaves.map((l) => new RAPIER.Ball(l[3]));
    const positions = leaves.map((l) => ({ x: l[0], y: l[1], z: l[2] }));
    const rotations = leaves.map(() => ({ x: 0, y: 0, z: 0, w: 1 }));
    this.bodies = [];
    const n = startPoses.length / POSE_FLOATS;
    for (let i = 0; i < n; i++) {
      const p = startPoses.subarray(i * POSE_FLOATS, (i + 1) * POSE_FLOATS);
      const desc = RAPIER.RigidBodyDesc.dynamic()
        .setTranslation(p[0], p[1], p[2])
        .setRotation({ x: p[3], y: p[4], z: p[5], w: p[6] })
        .setAdditionalMassProperties(setup.mass, v3(setup.center_of_mass), v3(setup.principal_inertia), frame)
        .setAngularDamping(setup.angular_damping)
        .setCcdEnabled(setup.ccd)
        .setCanSleep(setup.can_sleep);
      const body = world.createRigidBody(desc);
      world.createCollider(
        RAPIER.ColliderDesc.compound(balls, positions, rotations)
          .setDensity(0)
          .setFriction(setup.friction)
          .setRestitution(setup.restitution),
        body,
      );
      this.bodies.push(body);
    }
    this.world = world;
    this.stepped = false;
    this.weight = v3(setup.weight);
  }

  /** Weight at the centre of mass; buoyancy and drag at the centre of buoyancy. */
  applyForces(body) {
    const s = this.setup;
    const v = body.linvel();
    const speed = Math.hypot(v.x, v.y, v.z);
    const k = -s.drag_factor * speed;
    const t = body.translation();
    const r = rotate(body.rotation(), s.center_of_buoyancy);
    body.resetForces(false);
    body.resetTorques(false);
    body.addForce(this.weight, false);
    body.addForceAtPoint(
      { x: s.buoyancy[0] + k * v.x, y: s.buoyancy[1] + k * v.y, z: s.buoyancy[2] + k * v.z },
      { x: t.x + r[0], y: t.y + r[1], z: t.z + r[2] },
      false,
    );
  }

  step() {
    if (this.stepped) {
      this.world.forEachActiveRigidBody((body) => this.applyForces(body));
    } else {
      // Rapier registers the bodies with its islands during the first step.
      for (const body of this.bodies) this.applyForces(body);
    }
    this.world.step();
    this.stepped = true;
  }

  poses() {
    const out = new Float32Array(this.bodies.length * POSE_FLOATS);
    this.bodies.forEach((b, i) => {
      const t = b.translation();
      const q = b.rotation();
      out.set([t.x, t.y, t.z, q.x, q.y, q.z, q.w], i * POSE_FLOATS);
    });
    return out;
  }

  awakeCount() {
    let n = 0;
    for (const b of this.bodies) if (!b.isSleeping()) n++;
    return n;
  }
}

async function buildEngines(opts, exported, names) {
  // UP builds the scene for every engine; it runs on opts.threads only where it is timed.
  const up = await UpWasm.load(names.includes('up') ? opts.threads : 1, opts.threaded || opts.threads > 1);
  up.loadSceneJson(JSON.stringify(exported.scene));
  if (up.bodyCount() !== exported.balloons) {
    throw new Error(`UP's wasm built ${up.bodyCount()} balloons, expected ${exported.balloons}`);
  }
  const leaves = up.leaves();
  const same = leaves.length === exported.rapier.leaves.length &&
    leaves.every((l, i) => l.every((x, j) => Math.abs(x - exported.rapier.leaves[i][j]) < 1e-6));
  if (!same) throw new Error("the wasm build's balloon tree differs from up-bench's: rebuild both");
  const engines = [];
  for (const name of names) {
    if (name === 'up') engines.push(new UpEngine(up, opts.threads));
    else if (name === 'jolt') {
      const { Jolt, dispose } = await loadJolt(opts.threads);
      cleanups.push(dispose);
      engines.push(new JoltEngine(Jolt, opts.threads, exported.rapier, up.room(), up.poses(), leaves, POSE_FLOATS));
    } else {
      engines.push(new RapierEngine(await loadRapier(name), name, exported.rapier, up.room(), up.poses(), leaves));
    }
  }
  return engines;
}

// ---- statistics, as crates/up-bench/src/stats.rs ----

function quantile(samples, q) {
  const s = [...samples].sort((a, b) => a - b);
  const rank = Math.ceil(Math.min(Math.max(q, 0), 1) * s.length);
  return s[Math.min(Math.max(rank, 1), s.length) - 1];
}
const median = (s) => quantile(s, 0.5);
const mean = (s) => s.reduce((a, b) => a + b, 0) / s.length;
const settled = (s) => s.slice(s.length - Math.ceil(s.length / 3));

/**
 * MB of this process's peak resident set: VmHWM, as the native harness reads it.
 * (Not `resourceUsage().maxRSS`: Linux carries that across exec, so a child
 * would start with its parent's peak.)
 */
function peakRssMb() {
  try {
    const line = readFileSync('/proc/self/status', 'utf8').split('\n').find((l) => l.startsWith('VmHWM:'));
    if (line) return (Number(line.split(/\s+/)[1]) * 1024) / 1e6;
  } catch {
    // Not Linux: fall through.
  }
  return (process.resourceUsage().maxRSS * 1024) / 1e6;
}

/** Overlap and escapes of recorded frames, measured by up-bench (the native measure). */
function measure(opts, frames) {
  const dir = mkdtempSync(join(tmpdir(), 'up-bench-'));
  try {
    const file = join(dir, 'poses.f32');
    const all = new Float32Array(frames.reduce((n, f) => n + f.length, 0));
    let at = 0;
    for (const f of frames) {
      all.set(f, at);
      at += f.length;
    }
    writeFileSync(file, Buffer.from(all.buffer));
    const text = execFileSync(opts.upBench, ['measure', '--balloons', String(opts.balloons), '--seed', String(opts.seed), '--poses', file], {
      encoding: 'utf8',
    });
    return JSON.parse(text);
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
}

function probeInChild(opts, engine, steps) {
  const args = [fileURLToPath(import.meta.url), '--rss-probe', engine, '--balloons', String(opts.balloons), '--seed', String(opts.seed), '--steps', String(steps), '--threads', String(opts.threads), ...(opts.threaded ? ['--threaded'] : []), '--up-bench', opts.upBench];
  const r = spawnSync(process.execPath, args, { encoding: 'utf8', maxBuffer: 1 << 24 });
  if (r.status !== 0) throw new Error(`memory probe for ${engine} failed: ${r.stderr.trim()}`);
  return JSON.parse(r.stdout.trim().split('\n').pop());
}

async function rssProbe(opts) {
  const baseline = peakRssMb();
  const exported = loadScene(opts);
  const [engine] = await buildEngines(opts, exported, [opts.rssProbe]);
  const steps = opts.steps ?? exported.default_steps;
  for (let i = 0; i < steps; i++) engine.step();
  console.log(JSON.stringify({ baseline_rss_mb: baseline, peak_rss_mb: peakRssMb() }));
}

async function main() {
  const opts = parseArgs(process.argv);
  if (opts.rssProbe) return rssProbe(opts);
  const exported = loadScene(opts);
  const steps = opts.steps ?? exported.default_steps;
  const engines = await buildEngines(opts, exported, opts.engines);
  const times = engines.map(() => []);
  const frames = engines.map(() => []);
  // Poses at every step (or every k-th: at most pose_budget of them per
  // engine), measured after the timed loop, as the native harness does.
  const every = Math.max(1, Math.ceil((opts.balloons * steps) / exported.pose_budget));
  const timed = opts.threadTimes ? engines.find((e) => e.name === 'up') : null;
  if (timed) {
    timed.up.threadTimes(); // the sums start with the first timed step
    timed.up.setThreadTiming(true);
  }
  for (let step = 1; step <= steps; step++) {
    // Alternate who goes first, as the native harness does.
    const order = step % 2 === 1 ? engines.keys() : [...engines.keys()].reverse();
    for (const i of order) {
      const t0 = performance.now();
      engines[i].step();
      times[i].push(performance.now() - t0);
    }
    if (step % every === 0 || step === steps) {
      engines.forEach((e, i) => frames[i].push(e.poses()));
    }
  }
  const threadTimes = timed ? timed.up.threadTimes() : null;
  if (timed) timed.up.setThreadTiming(false);
  const results = engines.map((e, i) => {
    const m = measure(opts, frames[i]);
    const rss = opts.rss ? probeInChild(opts, e.name, steps) : null;
    const t = times[i];
    return {
      engine: e.name,
      runtime: 'wasm-node',
      balloons: opts.balloons,
      steps,
      threads: e.threads,
      ...(e.name === 'up' && opts.threaded ? { threaded: true } : {}),
      ms_per_step_median: median(t),
      ms_per_step_p95: quantile(t, 0.95),
      ms_per_step_mean: mean(t),
      settled_ms_per_step_median: median(settled(t)),
      max_penetration_m: m.max_penetration_m,
      final_penetration_m: m.final_penetration_m,
      escaped: m.escaped,
      awake_at_end: e.awakeCount(),
      peak_rss_mb: rss ? rss.peak_rss_mb : null,
      rss_bytes_per_balloon: rss ? ((rss.peak_rss_mb - rss.baseline_rss_mb) * 1e6) / opts.balloons : null,
      room_width_m: exported.room_width_m,
      ...(e === timed ? { stage_threads_mean: threadTimes } : {}),
      ...(e.name.startsWith('rapier') ? { rapier_shape: 'compound' } : {}),
      ...(e.name === 'up' ? {} : { package: PACKAGES[e.name], version: packageVersion(PACKAGES[e.name]) }),
    };
  });
  const up = results.find((r) => r.engine === 'up');
  // Each peer over UP by the median, and by the mean (total time), when both
  // ran: ratio_rapier_over_up, ratio_rapier_simd_over_up, ratio_jolt_over_up.
  const peers = results.filter((r) => r.engine !== 'up');
  const ratios = up && peers.length
    ? Object.fromEntries(
        peers.flatMap((r) => {
          const key = `ratio_${r.engine.replace('-', '_')}_over_up`;
          return [
            [key, r.ms_per_step_median / up.ms_per_step_median],
            [`${key}_mean`, r.ms_per_step_mean / up.ms_per_step_mean],
          ];
        }),
      )
    : null;
  if (opts.json) {
    for (const r of results) console.log(JSON.stringify(r));
    if (ratios) console.log(JSON.stringify(ratios));
  } else {
    for (const r of results) {
      console.log(
        `${r.engine.padEnd(7)} ${r.balloons} balloons, ${r.steps} steps: median ${r.ms_per_step_median.toFixed(3)} ms, ` +
          `p95 ${r.ms_per_step_p95.toFixed(3)} ms, settled ${r.settled_ms_per_step_median.toFixed(3)} ms, ` +
          `max penetration ${(r.max_penetration_m * 1e3).toFixed(3)} mm, escaped ${r.escaped}, awake ${r.awake_at_end}, ` +
          `peak RSS ${r.peak_rss_mb === null ? '-' : r.peak_rss_mb.toFixed(1)} MB`,
      );
      if (r.stage_threads_mean) process.stdout.write(threadTable(r.stage_threads_mean));
    }
    for (const r of up ? peers : []) {
      const key = `ratio_${r.engine.replace('-', '_')}_over_up`;
      console.log(
        `${r.engine} (${r.threads} thread${r.threads === 1 ? '' : 's'}) / UP (${up.threads}): median ms per step ${ratios[key].toFixed(2)}; ` +
          `mean (total time) ${ratios[`${key}_mean`].toFixed(2)}; max penetration ${(r.max_penetration_m * 1e3).toFixed(3)} mm against UP's ${(up.max_penetration_m * 1e3).toFixed(3)} mm`,
      );
    }
  }
}

main()
  .then(() => {
    for (const dispose of cleanups) dispose();
    // Jolt's worker threads would keep Node alive.
    process.exit(0);
  })
  .catch((e) => {
    for (const dispose of cleanups) dispose();
    console.error(`bench.mjs: ${e.message}`);
    process.exit(1);
  });
