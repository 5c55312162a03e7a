// Jolt (npm jolt-physics) built to match the bench scene, as bench.mjs builds
// Rapier: the same room, the same compounds of leaf spheres, the same start
// poses, masses, inertia, forces and sleep thresholds.
//
// One thread: the `wasm-compat` flavour. T > 1 threads: `wasm-compat-multithread`
// with T − 1 workers in Jolt's job system (the calling thread runs jobs too).

import { mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import { tmpdir } from 'node:os';
import { dirname, join } from 'node:path';
import { pathToFileURL } from 'node:url';

const require = createRequire(import.meta.url);
const MULTITHREAD_FILE = 'jolt-physics.multithread.wasm-compat.js';
/**
 * The multithreaded bundle tests `await import("node:worker_threads").workerData`,
 * which reads `.workerData` off the promise, so in Node its pthread workers never
 * start and the factory never resolves. The bundle is loaded from a copy with
 * that expression parenthesised (its workers load the file next to it: the copy).
 */
const PTHREAD_TEST = 'await import("node:worker_threads").workerData';
const PTHREAD_FIXED = '(await import("node:worker_threads")).workerData';

/**
 * JoltInterface steps with a fixed 10 MB temporary allocator (not settable from
 * JS), from which each step takes room for mMaxContactConstraints constraints
 * (≈ 472 bytes each) and per-body lists (≈ 144 bytes a body): past it the module
 * aborts. The caps below are those found to fit (20,000 at 1,000 bodies, 8,192
 * at 10,000); past them Jolt ignores the contacts that do not fit (a pile of
 * 10,000 balloons has more).
 */
export function joltContactCap(bodies) {
  return Math.min(bodies * 32, bodies <= 2000 ? 20000 : 8192);
}

const LAYER_ROOM = 0;
const LAYER_BALLOON = 1;

/** The Jolt module of the flavour for `threads`, and a function that removes its temporary copy. */
export async function loadJolt(threads) {
  if (threads <= 1) {
    const factory = (await import('jolt-physics/wasm-compat')).default;
    return { Jolt: await factory(), dispose() {} };
  }
  const dist = join(dirname(require.resolve('jolt-physics/package.json')), 'dist');
  const text = readFileSync(join(dist, MULTITHREAD_FILE), 'utf8');
  const found = text.split(PTHREAD_TEST).length - 1;
  if (found !== 1) {
    throw new Error(`jolt-physics: expected its pthread test once in ${MULTITHREAD_FILE}, found it ${found} times (another version? check whether it starts its workers in Node)`);
  }
  const dir = mkdtempSync(join(tmpdir(), 'up-bench-jolt-'));
  const file = join(dir, MULTITHREAD_FILE);
  writeFileSync(file, text.replace(PTHREAD_TEST, PTHREAD_FIXED));
  const factory = (await import(pathToFileURL(file).href)).default;
  return { Jolt: await factory(), dispose: () => rmSync(dir, { recursive: true, force: true }) };
}

function rotate(q, v) {
  // v + 2·w·(u × v) + 2·u × (u × v), u = (qx, qy, qz).
  const tx = 2 * (q[1] * v[2] - q[2] * v[1]);
  const ty = 2 * (q[2] * v[0] - q[0] * v[2]);
  const tz = 2 * (q[0] * v[1] - q[1] * v[0]);
  return [
    v[0] + q[3] * tx + (q[1] * tz - q[2] * ty),
    v[1] + q[3] * ty + (q[2] * tx - q[0] * tz),
    v[2] + q[3] * tz + (q[0] * ty - q[1] * tx),
  ];
}

export class JoltEngine {
  /**
   * `setup`: up-bench's matched parameters (the `rapier` object of --print-scene);
   * `room`: UP's room triangles; `startPoses`: UP's poses (x, y, z, qx, qy, qz, qw);
   * `leaves`: [x, y, z, r] of the balloon's leaf spheres in the body frame.
   */
  constructor(Jolt, threads, setup, room, startPoses, leaves, poseFloats) {
    this.name = 'jolt';
    this.Jolt = Jolt;
    this.threads = threads;
    this.setup = setup;
    this.poseFloats = poseFloats;
    const n = startPoses.length / poseFloats;

    const settings = new Jolt.JoltSettings();
    settings.mMaxWorkerThreads = Math.max(0, threads - 1);
    settings.mMaxBodies = n + 16;
    settings.mMaxBodyPairs = n * 32;
    settings.mMaxContactConstraints = joltContactCap(n);
    const pairs = new Jolt.ObjectLayerPairFilterTable(2);
    pairs.EnableCollision(LAYER_ROOM, LAYER_BALLOON);
    pairs.EnableCollision(LAYER_BALLOON, LAYER_BALLOON);
    const layers = new Jolt.BroadPhaseLayerInterfaceTable(2, 2);
    layers.MapObjectToBroadPhaseLayer(LAYER_ROOM, new Jolt.BroadPhaseLayer(0));
    layers.MapObjectToBroadPhaseLayer(LAYER_BALLOON, new Jolt.BroadPhaseLayer(1));
    settings.mObjectLayerPairFilter = pairs;
    settings.mBroadPhaseLayerInterface = layers;
    settings.mObjectVsBroadPhaseLayerFilter = new Jolt.ObjectVsBroadPhaseLayerFilterTable(layers, 2, pairs, 2);
    this.jolt = new Jolt.JoltInterface(settings);
    Jolt.destroy(settings);
    const system = this.jolt.GetPhysicsSystem();
    this.system = system;
    // Weight is applied as a force (the mass holds the added mass), as for Rapier.
    system.SetGravity(new Jolt.Vec3(0, 0, 0));
    const ps = system.GetPhysicsSettings();
    // Jolt's solver is not substepped: as many velocity passes as Rapier's
    // substeps × internal passes (UP's substeps × Gauss–Seidel passes).
    ps.mNumVelocitySteps = setup.num_solver_iterations * setup.num_internal_pgs_iterations;
    // Rapier's allowed penetration (its default 1 mm) instead of Jolt's 2 cm.
    ps.mPenetrationSlop = 0.001;
    ps.mPointVelocitySleepThreshold = setup.sleep_speed;
    ps.mTimeBeforeSleep = setup.time_until_sleep;
    ps.mAllowSleeping = setup.can_sleep;
    system.SetPhysicsSettings(ps);
    const bodies = system.GetBodyInterface();

    // The room: one-sided triangles, as Rapier's TriMesh.
    const tris = new Jolt.TriangleList();
    const v = room.vertices;
    const t = room.triangles;
    const corner = [new Jolt.Vec3(0, 0, 0), new Jolt.Vec3(0, 0, 0), new Jolt.Vec3(0, 0, 0)];
    for (let i = 0; i < t.length; i += 3) {
      for (let k = 0; k < 3; k++) corner[k].Set(v[t[i + k] * 3], v[t[i + k] * 3 + 1], v[t[i + k] * 3 + 2]);
      const tri = new Jolt.Triangle(corner[0], corner[1], corner[2]);
      tris.push_back(tri);
      Jolt.destroy(tri);
    }
    const roomShape = new Jolt.MeshShapeSettings(tris).Create().Get();
    const roomSettings = new Jolt.BodyCreationSettings(roomShape, new Jolt.RVec3(0, 0, 0), new Jolt.Quat(0, 0, 0, 1), Jolt.EMotionType_Static, LAYER_ROOM);
    roomSettings.mFriction = setup.friction;
    roomSettings.mRestitution = setup.restitution;
    bodies.CreateAndAddBody(roomSettings, Jolt.EActivation_DontActivate);
    Jolt.destroy(roomSettings);

    // A balloon: its leaf spheres in a static compound, the centre of mass moved to UP's.
    const compound = new Jolt.StaticCompoundShapeSettings();
    const origin = new Jolt.Quat(0, 0, 0, 1);
    for (const l of leaves) compound.AddShape(new Jolt.Vec3(l[0], l[1], l[2]), origin, new Jolt.SphereShapeSettings(l[3]), 0);
    const plain = compound.Create().Get();
    const c = plain.GetCenterOfMass();
    const com = setup.center_of_mass;
    const shape = new Jolt.OffsetCenterOfMassShapeSettings(new Jolt.Vec3(com[0] - c.GetX(), com[1] - c.GetY(), com[2] - c.GetZ()), compound).Create().Get();
    shape.AddRef();
    this.shape = shape;

    const mass = new Jolt.MassProperties();
    mass.mMass = setup.mass;
    const pi = setup.principal_inertia;
    mass.mInertia = Jolt.Mat44.prototype.sScaleVec3(new Jolt.Vec3(pi[0], pi[1], pi[2]));
    const f = setup.inertia_frame;
    mass.Rotate(Jolt.Mat44.prototype.sRotation(new Jolt.Quat(f[0], f[1], f[2], f[3])));

    this.bodies = [];
    const pos = new Jolt.RVec3(0, 0, 0);
    const rot = new Jolt.Quat(0, 0, 0, 1);
    for (let i = 0; i < n; i++) {
      const p = startPoses.subarray(i * poseFloats, (i + 1) * poseFloats);
      pos.Set(p[0], p[1], p[2]);
      rot.Set(p[3], p[4], p[5], p[6]);
      const bcs = new Jolt.BodyCreationSettings(shape, pos, rot, Jolt.EMotionType_Dynamic, LAYER_BALLOON);
      bcs.mOverrideMassProperties = Jolt.EOverrideMassProperties_MassAndInertiaProvided;
      bcs.mMassPropertiesOverride = mass;
      bcs.mLinearDamping = 0;
      bcs.mAngularDamping = setup.angular_damping;
      bcs.mFriction = setup.friction;
      bcs.mRestitution = setup.restitution;
      bcs.mMotionQuality = setup.ccd ? Jolt.EMotionQuality_LinearCast : Jolt.EMotionQuality_Discrete;
      bcs.mAllowSleeping = setup.can_sleep;
      const body = bodies.CreateBody(bcs);
      Jolt.destroy(bcs);
      bodies.AddBody(body.GetID(), Jolt.EActivation_Activate);
      this.bodies.push(body);
    }
    // Body ids → bodies, for the active list.
    this.byIndex = [];
    for (const b of this.bodies) this.byIndex[b.GetID().GetIndex()] = b;
    system.OptimizeBroadPhase();
    this.active = new Jolt.BodyIDVector();
    this.force = new Jolt.Vec3(0, 0, 0);
    this.weight = new Jolt.Vec3(setup.weight[0], setup.weight[1], setup.weight[2]);
    this.at = new Jolt.RVec3(0, 0, 0);
    this.q = [0, 0, 0, 1];
  }

  /** Weight at the centre of mass; buoyancy and drag at the centre of buoyancy (Jolt clears forces after a step). */
  applyForces(body) {
    const s = this.setup;
    const v = body.GetLinearVelocity();
    const vx = v.GetX();
    const vy = v.GetY();
    const vz = v.GetZ();
    const k = -s.drag_factor * Math.hypot(vx, vy, vz);
    const t = body.GetPosition();
    const r = body.GetRotation();
    const q = this.q;
    q[0] = r.GetX();
    q[1] = r.GetY();
    q[2] = r.GetZ();
    q[3] = r.GetW();
    const c = rotate(q, s.center_of_buoyancy);
    this.at.Set(t.GetX() + c[0], t.GetY() + c[1], t.GetZ() + c[2]);
    this.force.Set(s.buoyancy[0] + k * vx, s.buoyancy[1] + k * vy, s.buoyancy[2] + k * vz);
    body.AddForce(this.weight);
    body.AddForce(this.force, this.at);
  }

  step() {
    const Jolt = this.Jolt;
    this.system.GetActiveBodies(Jolt.EBodyType_RigidBody, this.active);
    const m = this.active.size();
    for (let i = 0; i < m; i++) {
      const body = this.byIndex[this.active.at(i).GetIndex()];
      if (body) this.applyForces(body);
    }
    this.jolt.Step(this.setup.dt, 1);
  }

  poses() {
    const out = new Float32Array(this.bodies.length * this.poseFloats);
    this.bodies.forEach((b, i) => {
      const t = b.GetPosition();
      const q = b.GetRotation();
      out.set([t.GetX(), t.GetY(), t.GetZ(), q.GetX(), q.GetY(), q.GetZ(), q.GetW()], i * this.poseFloats);
    });
    return out;
  }

  awakeCount() {
    let n = 0;
    for (const b of this.bodies) if (b.IsActive()) n++;
    return n;
  }
}
