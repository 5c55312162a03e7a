// Squash on impact, drawn only (the physics stays rigid: docs/physics.md,
// "Squash is drawn"). Each frame from the worker carries every body's deepest
// dent since the frame before (up-wasm's squash.rs): the normal times the
// depth, and the reach from the body's origin to the contact along it. The
// page keeps, per body, the deepest dent still showing and lets it spring
// back, d(t) = d₀·exp(−t/τ) from the step that made it, the same at any frame
// rate; every animation frame writes the depths now into one instanced vec4
// attribute, and the balloons' vertex shader flattens each instance against
// its contact plane and widens it a little around the normal so its volume
// is about kept.

import * as THREE from "three";
import { SQUASH_STRIDE } from "../sim/frameLayout";

/**
 * How fast a dent springs back, s. The contact itself lasts half the
 * membrane's period, π·√(m/k) ≈ 10 ms for an 11″ balloon at 2 kPa, under a
 * frame; the membrane then rings for a few periods as the balloon leaves.
 * 40 ms (an estimate: no measurement found) shows a 5 m/s impact for a few
 * frames at 60 fps, as a filmed one reads.
 */
export const SQUASH_RETURN_S = 0.04;
/** Shallowest dent drawn, m: the engine's threshold halved, so a dent fades out rather than snaps. */
export const SQUASH_MIN_DRAWN_M = 0.0005;

/** Name of the instanced attribute the balloons' vertex shader reads. */
export const SQUASH_ATTRIBUTE = "squash";

/**
 * Depth of a dent `ageS` seconds after the step that made it, m: exponential
 * spring-back, 0 once under `SQUASH_MIN_DRAWN_M` (and for a dent yet to come).
 */
export function springBack(depth: number, ageS: number): number {
  const d = depth * Math.exp(-Math.max(0, ageS) / SQUASH_RETURN_S);
  return d >= SQUASH_MIN_DRAWN_M ? d : 0;
}

/** The dents showing, per body (dense order), and their spring-back. */
export class SquashDents {
  /** Per body: unit normal (x, y, z), the reach (m) and the depth when made (m). */
  private normals = new Float32Array(0);
  private reach = new Float32Array(0);
  private depth = new Float32Array(0);
  /** Absolute time (ms since the epoch) each dent was made. */
  private made = new Float64Array(0);
  /**
   * Per body, the deepest dent taken since the bodies were set (normal,
   * reach, depth, when): what the test hook reads, since on a page slower
   * than the bounces a dent may be replaced or sprung back before it looks.
   */
  private peakNormals = new Float32Array(0);
  private peakReach = new Float32Array(0);
  private peakDepth = new Float32Array(0);
  private peakMade = new Float64Array(0);
  private count = 0;

  /** Forgets every dent (new bodies or a new order), for `count` bodies. */
  reset(count: number): void {
    if (count > this.depth.length) {
      const n = Math.max(count, this.depth.length * 2);
      this.normals = new Float32Array(n * 3);
      this.reach = new Float32Array(n);
      this.depth = new Float32Array(n);
      this.made = new Float64Array(n);
      this.peakNormals = new Float32Array(n * 3);
      this.peakReach = new Float32Array(n);
      this.peakDepth = new Float32Array(n);
      this.peakMade = new Float64Array(n);
    }
    this.depth.fill(0);
    this.peakDepth.fill(0);
    this.count = count;
  }

  /**
   * Takes a frame's dents (`SQUASH_STRIDE` per body) made at `stepTime`
   * (ms since the epoch): a body's new dent replaces the one showing when it
   * is deeper than what is left of that.
   */
  add(table: Float32Array, stepTime: number): void {
    const n = Math.min(this.count, Math.floor(table.length / SQUASH_STRIDE));
    for (let i = 0; i < n; i++) {
      const o = i * SQUASH_STRIDE;
      const x = table[o];
      const y = table[o + 1];
      const z = table[o + 2];
      const d = Math.hypot(x, y, z);
      if (!(d > 0)) continue;
      if (d > this.peakDepth[i]) {
        this.peakNormals.set([x / d, y / d, z / d], 3 * i);
        this.peakReach[i] = table[o + 3];
        this.peakDepth[i] = d;
        this.peakMade[i] = stepTime;
      }
      if (d <= springBack(this.depth[i], (stepTime - this.made[i]) / 1000)) continue;
      this.normals[3 * i] = x / d;
      this.normals[3 * i + 1] = y / d;
      this.normals[3 * i + 2] = z / d;
      this.reach[i] = table[o + 3];
      this.depth[i] = d;
      this.made[i] = stepTime;
    }
  }

  /** Body `i`'s dent `ageMs` after it was made (normal × depth, reach; zeros: none or sprung back). */
  at(i: number, ageMs: number): [number, number, number, number] {
    const d = i < this.count && this.depth[i] > 0 ? springBack(this.depth[i], ageMs / 1000) : 0;
    if (d === 0) return [0, 0, 0, 0];
    return [this.normals[3 * i] * d, this.normals[3 * i + 1] * d, this.normals[3 * i + 2] * d, this.reach[i]];
  }

  /** Body `i`'s deepest dent since the bodies were set, `ageMs` after it was made (as `at`), and when it was made (null: none). */
  peak(i: number, agesMs: number[]): { at: [number, number, number, number][]; madeAt: number | null } {
    const depth = i < this.count ? this.peakDepth[i] : 0;
    if (!(depth > 0)) return { at: agesMs.map(() => [0, 0, 0, 0]), madeAt: null };
    const at = agesMs.map((ms): [number, number, number, number] => {
      const d = springBack(depth, ms / 1000);
      if (d === 0) return [0, 0, 0, 0];
      return [this.peakNormals[3 * i] * d, this.peakNormals[3 * i + 1] * d, this.peakNormals[3 * i + 2] * d, this.peakReach[i]];
    });
    return { at, madeAt: this.peakMade[i] };
  }

  /** When body `i`'s dent was made, ms since the epoch (null: none showing). */
  madeAt(i: number): number | null {
    return i < this.count && this.depth[i] > 0 ? this.made[i] : null;
  }

  /**
   * Writes every body's dent at `now` (ms since the epoch) into `out`, four
   * floats each: the unit normal and the depth (zeros: none); returns how
   * many bodies have one.
   */
  write(out: Float32Array, now: number): number {
    let dented = 0;
    const n = Math.min(this.count, Math.floor(out.length / 4));
    for (let i = 0; i < n; i++) {
      const d = this.depth[i] > 0 ? springBack(this.depth[i], (now - this.made[i]) / 1000) : 0;
      const o = 4 * i;
      if (d === 0) {
        if (this.depth[i] > 0) this.depth[i] = 0;
        out[o] = out[o + 1] = out[o + 2] = out[o + 3] = 0;
        continue;
      }
      dented++;
      out[o] = this.normals[3 * i] * d;
      out[o + 1] = this.normals[3 * i + 1] * d;
      out[o + 2] = this.normals[3 * i + 2] * d;
      out[o + 3] = this.reach[i];
    }
    return dented;
  }
}

/** The vertex shader's part, in the instance's own frame (before `instanceMatrix`). */
const SQUASH_COMMON = /* glsl */ `
attribute vec4 ${SQUASH_ATTRIBUTE};
// The dent in the instance's frame: unit normal, the plane's distance from the
// origin along it, the depth, and the widening that keeps the volume.
struct Dent { vec3 n; float plane; float depth; float widen; };
Dent upDent() {
  Dent dent = Dent(vec3(0.0, 1.0, 0.0), 1e9, 0.0, 0.0);
  float d = length(${SQUASH_ATTRIBUTE}.xyz);
  if (d <= 0.0) return dent;
  mat3 m = mat3(instanceMatrix);
  float s = length(m[0]);
  if (s <= 0.0) return dent;
  // World normal into the instance's frame: mat3 is rotation times s.
  dent.n = normalize(transpose(m) * (${SQUASH_ATTRIBUTE}.xyz / d));
  float reach = ${SQUASH_ATTRIBUTE}.w / s;
  dent.depth = d / s;
  dent.plane = reach - dent.depth;
  // A cap of depth d cut from a sphere of radius R holds π·d²·(R − d/3);
  // widening across the normal by w gains 2·w of the volume (4/3)·π·R³.
  float r = max(reach, 2.0 * dent.depth);
  dent.widen = 0.375 * dent.depth * dent.depth * (r - dent.depth / 3.0) / (r * r * r);
  return dent;
}
`;

/**
 * Makes `material` draw each instance squashed by its `squash` attribute
 * (xyz: the dent's world normal times its depth, m; w: the reach from the
 * instance's origin to the contact along the normal, m): vertices past the
 * plane `reach − depth` out along the normal are laid onto it, with the
 * normal's own direction for shading, and the rest is widened across the
 * normal to keep the volume. A zero attribute leaves the instance as it is.
 */
export function addSquash(material: THREE.Material): void {
  const before = material.onBeforeCompile.bind(material);
  material.onBeforeCompile = (shader, renderer) => {
    before(shader, renderer);
    shader.vertexShader = shader.vertexShader
      .replace("#include <common>", `#include <common>\n${SQUASH_COMMON}`)
      .replace(
        "#include <beginnormal_vertex>",
        `#include <beginnormal_vertex>
        Dent upSquash = upDent();
        {
          float along = dot(position, upSquash.n);
          // The flattened patch faces along the normal; its rim blends in over a depth.
          float flattened = smoothstep(upSquash.plane - upSquash.depth, upSquash.plane, along);
          objectNormal = normalize(mix(objectNormal, upSquash.n, flattened));
        }`,
      )
      .replace(
        "#include <begin_vertex>",
        `#include <begin_vertex>
        {
          float along = dot(transformed, upSquash.n);
          transformed -= upSquash.n * max(0.0, along - upSquash.plane);
          vec3 across = transformed - upSquash.n * dot(transformed, upSquash.n);
          transformed += across * upSquash.widen;
        }`,
      );
  };
  const key = material.customProgramCacheKey.bind(material);
  material.customProgramCacheKey = () => `${key()}|squash`;
}
