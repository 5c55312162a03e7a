// The ribbons' strips on the CPU, for the photo: the live view places a
// ribbon's vertices in its vertex shader (ribbons.ts, `ribbonVertex`), which
// the path tracer never runs, so the same curve, twist and curl are computed
// here, vertex for vertex, from the same points and the same constants.

import { CURL_LENGTH, CURL_RADIUS, CURL_SAMPLES, CURL_TURNS, STRIP_SAMPLES, TWIST_TURNS_PER_M } from "../ribbons";

type Vec3 = [number, number, number];

/** Vertices of one ribbon's strip: two per sample (sides −1, +1), as ribbons.ts's `stripTemplate`. */
export const STRIP_VERTICES = 2 * (STRIP_SAMPLES + CURL_SAMPLES + 1);

/** One ribbon as the live view's `ribbon` attribute holds it: first point, point count, length (m), phase (rad). */
export interface RibbonRow {
  first: number;
  count: number;
  length: number;
  phase: number;
}

const add = (a: Vec3, b: Vec3): Vec3 => [a[0] + b[0], a[1] + b[1], a[2] + b[2]];
const scale = (a: Vec3, s: number): Vec3 => [a[0] * s, a[1] * s, a[2] * s];
const cross = (a: Vec3, b: Vec3): Vec3 => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
const len = (a: Vec3): number => Math.hypot(a[0], a[1], a[2]);
const normalize = (a: Vec3): Vec3 => scale(a, 1 / (len(a) || 1));
const clamp = (x: number, lo: number, hi: number) => Math.min(hi, Math.max(lo, x));
const smoothstep = (e0: number, e1: number, x: number) => {
  const t = clamp((x - e0) / (e1 - e0), 0, 1);
  return t * t * (3 - 2 * t);
};

/**
 * Writes ribbon `row`'s strip into `positions` and `normals` (3 floats per
 * vertex, from vertex `at`): `texels` holds the points as RGBA (4 floats a
 * point), as the live view's points texture does.
 */
export function writeRibbonStrip(
  texels: Float32Array,
  row: RibbonRow,
  halfWidth: number,
  positions: Float32Array,
  normals: Float32Array,
  at: number,
): void {
  const n = row.count;
  const point = (i: number): Vec3 => {
    const k = (row.first + Math.trunc(clamp(i, 0, n - 1))) * 4;
    return [texels[k], texels[k + 1], texels[k + 2]];
  };
  const curve = (f: number): { p: Vec3; d: Vec3 } => {
    const i = clamp(Math.floor(f), 0, n - 2);
    const t = clamp(f - i, 0, 1);
    const p1 = point(i);
    const p2 = point(i + 1);
    const p0 = i > 0 ? point(i - 1) : add(scale(p1, 2), scale(p2, -1));
    const p3 = i + 2 < n ? point(i + 2) : add(scale(p2, 2), scale(p1, -1));
    const d: Vec3 = [0, 0, 0];
    const p: Vec3 = [0, 0, 0];
    for (let c = 0; c < 3; c++) {
      const a = 2 * p1[c];
      const b = p2[c] - p0[c];
      const cc = 2 * p0[c] - 5 * p1[c] + 4 * p2[c] - p3[c];
      const dd = -p0[c] + 3 * p1[c] - 3 * p2[c] + p3[c];
      d[c] = 0.5 * (b + 2 * cc * t + 3 * dd * t * t);
      p[c] = 0.5 * (a + b * t + cc * t * t + dd * t * t * t);
    }
    return { p, d };
  };
  const length = Math.max(row.length, 1e-4);
  const curlLength = Math.min(CURL_LENGTH, 0.5 * length);
  const straight = length - curlLength;
  const curlAngle = 2 * Math.PI * CURL_TURNS;
  let v = at;
  for (let k = 0; k <= STRIP_SAMPLES + CURL_SAMPLES; k++) {
    const s = k <= STRIP_SAMPLES ? (straight * k) / STRIP_SAMPLES : straight + (curlLength * (k - STRIP_SAMPLES)) / CURL_SAMPLES;
    const { p: centre, d } = curve((s / length) * (n - 1));
    const axis: Vec3 = len(d) > 1e-6 ? normalize(d) : [0, -1, 0];
    const reference: Vec3 = Math.abs(axis[0]) < 0.9 ? [1, 0, 0] : [0, 0, 1];
    const across = normalize(cross(axis, reference));
    const other = cross(axis, across);
    const u = clamp((s - straight) / Math.max(curlLength, 1e-4), 0, 1);
    const grow = smoothstep(0, 0.35, u);
    const radius = CURL_RADIUS * grow;
    const theta = row.phase + curlAngle * u;
    const radial = add(scale(across, Math.cos(theta)), scale(other, Math.sin(theta)));
    const swirl = add(scale(across, -Math.sin(theta)), scale(other, Math.cos(theta)));
    const centreline = add(centre, scale(radial, radius));
    const tangent = add(axis, scale(swirl, (radius * curlAngle) / Math.max(curlLength, 1e-4)));
    const phi = row.phase + 2 * Math.PI * TWIST_TURNS_PER_M * s;
    const twisted = add(scale(across, Math.cos(phi)), scale(other, Math.sin(phi)));
    const width = normalize(add(scale(twisted, 1 - grow), scale(axis, grow)));
    const rawNormal = cross(tangent, width);
    const normal = len(rawNormal) > 1e-8 ? normalize(rawNormal) : radial;
    for (const side of [-1, 1]) {
      const q = add(centreline, scale(width, side * halfWidth));
      positions.set(q, v * 3);
      normals.set(normal, v * 3);
      v++;
    }
  }
}

/** The strip's triangles for `ribbons` ribbons in a row, as ribbons.ts's `stripTemplate` (two per sample step). */
export function stripIndices(ribbons: number, firstVertex = 0): Uint32Array {
  const samples = STRIP_SAMPLES + CURL_SAMPLES + 1;
  const out = new Uint32Array(ribbons * (samples - 1) * 6);
  let o = 0;
  for (let r = 0; r < ribbons; r++) {
    const base = firstVertex + r * STRIP_VERTICES;
    for (let k = 1; k < samples; k++) {
      const a = base + 2 * (k - 1);
      out.set([a, a + 1, a + 2, a + 1, a + 3, a + 2], o);
      o += 6;
    }
  }
  return out;
}
