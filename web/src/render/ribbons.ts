// The ribbons: every ribbon in one instanced draw call. The main thread only
// writes the ribbons' points, interpolated between the frame's two steps,
// into one float texture a frame; the vertex shader turns them into thin
// curling ribbon: a flat strip 5 mm wide along a Catmull-Rom curve through
// the points, twisting along its length and winding into a helix over its
// last CURL_LENGTH (as curling ribbon does). Each instance is one ribbon: a
// strip of fixed samples (STRIP_SAMPLES along, CURL_SAMPLES in the curl)
// that the shader places on that ribbon's points. Lit (MeshStandardMaterial),
// double-sided, in each ribbon's colour; it casts no shadow. A weight at a
// free end is a small foil ball of the ribbon's colour (one instanced mesh).

import * as THREE from "three";
import type { RibbonTables } from "../sim/engine";
import { RIBBON_POINT_STRIDE } from "../sim/frameLayout";

/** Points per row of the points texture. */
export const TEXTURE_WIDTH = 1024;
/** Samples of a ribbon before its curl, and in its curl. */
export const STRIP_SAMPLES = 32;
export const CURL_SAMPLES = 48;
/** Length of ribbon wound into the curl at the free end, m (at most half the ribbon). */
export const CURL_LENGTH = 0.18;
/** Radius of the curl's helix, m, and its turns. */
export const CURL_RADIUS = 0.011;
export const CURL_TURNS = 6;
/** Turns of twist per metre along the straight part. */
export const TWIST_TURNS_PER_M = 1.2;

/** The strip every ribbon is drawn from: per vertex (sample index, side ±1, 0); two triangles per sample step. */
export function stripTemplate(): THREE.InstancedBufferGeometry {
  const samples = STRIP_SAMPLES + CURL_SAMPLES + 1;
  const position = new Float32Array(samples * 2 * 3);
  const index: number[] = [];
  for (let k = 0; k < samples; k++) {
    position.set([k, -1, 0, k, 1, 0], k * 6);
    if (k > 0) {
      const a = 2 * (k - 1);
      index.push(a, a + 1, a + 2, a + 1, a + 3, a + 2);
    }
  }
  const geometry = new THREE.InstancedBufferGeometry();
  geometry.setAttribute("position", new THREE.BufferAttribute(position, 3));
  geometry.setIndex(index);
  geometry.instanceCount = 0;
  return geometry;
}

/** The vertex shader's part: declarations, and the code that places a vertex and its normal. */
const VERTEX_HEAD = /* glsl */ `
uniform highp sampler2D ribbonPoints;
uniform int ribbonTextureWidth;
uniform float ribbonHalfWidth;
/** First point in the texture, point count, length (m), phase (rad). */
attribute vec4 ribbon;

vec3 ribbonPoint(float i) {
  int k = int(ribbon.x) + int(clamp(i, 0.0, ribbon.y - 1.0));
  return texelFetch(ribbonPoints, ivec2(k % ribbonTextureWidth, k / ribbonTextureWidth), 0).xyz;
}

/** The uniform Catmull-Rom curve through the points at point parameter f, and its derivative per point. */
vec3 ribbonCurve(float f, out vec3 derivative) {
  float n = ribbon.y;
  float i = clamp(floor(f), 0.0, n - 2.0);
  float t = clamp(f - i, 0.0, 1.0);
  vec3 p1 = ribbonPoint(i);
  vec3 p2 = ribbonPoint(i + 1.0);
  // Past the ends, the end segments continued.
  vec3 p0 = i > 0.0 ? ribbonPoint(i - 1.0) : 2.0 * p1 - p2;
  vec3 p3 = i + 2.0 < n ? ribbonPoint(i + 2.0) : 2.0 * p2 - p1;
  vec3 a = 2.0 * p1;
  vec3 b = p2 - p0;
  vec3 c = 2.0 * p0 - 5.0 * p1 + 4.0 * p2 - p3;
  vec3 d = -p0 + 3.0 * p1 - 3.0 * p2 + p3;
  derivative = 0.5 * (b + 2.0 * c * t + 3.0 * d * t * t);
  return 0.5 * (a + b * t + c * t * t + d * t * t * t);
}

void ribbonVertex(out vec3 outPosition, out vec3 outNormal) {
  float k = position.x;
  float side = position.y;
  float n = ribbon.y;
  float len = max(ribbon.z, 1e-4);
  float curlLength = min(${CURL_LENGTH.toFixed(4)}, 0.5 * len);
  float straight = len - curlLength;
  // Arc length of this sample: evenly along the straight part, then the curl.
  float s = k <= ${STRIP_SAMPLES.toFixed(1)}
    ? straight * k / ${STRIP_SAMPLES.toFixed(1)}
    : straight + curlLength * (k - ${STRIP_SAMPLES.toFixed(1)}) / ${CURL_SAMPLES.toFixed(1)};
  vec3 derivative;
  vec3 centre = ribbonCurve(s / len * (n - 1.0), derivative);
  vec3 axis = length(derivative) > 1e-6 ? normalize(derivative) : vec3(0.0, -1.0, 0.0);
  // A frame across the axis (a fixed reference; it turns only where the ribbon runs along x).
  vec3 reference = abs(axis.x) < 0.9 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 0.0, 1.0);
  vec3 across = normalize(cross(axis, reference));
  vec3 other = cross(axis, across);
  // Into the curl: 0 where it starts, 1 at the free end.
  float u = clamp((s - straight) / max(curlLength, 1e-4), 0.0, 1.0);
  float grow = smoothstep(0.0, 0.35, u);
  float radius = ${CURL_RADIUS.toFixed(4)} * grow;
  float theta = ribbon.w + ${(2 * Math.PI * CURL_TURNS).toFixed(4)} * u;
  vec3 radial = cos(theta) * across + sin(theta) * other;
  vec3 swirl = -sin(theta) * across + cos(theta) * other;
  vec3 centreline = centre + radius * radial;
  // Along the strip: the axis, plus the helix's turning.
  vec3 tangent = axis + radius * ${(2 * Math.PI * CURL_TURNS).toFixed(4)} / max(curlLength, 1e-4) * swirl;
  // Across the strip: twisting about the axis along the straight part, along the axis in the curl.
  float phi = ribbon.w + ${(2 * Math.PI * TWIST_TURNS_PER_M).toFixed(4)} * s;
  vec3 twisted = cos(phi) * across + sin(phi) * other;
  vec3 width = normalize(mix(twisted, axis, grow));
  outPosition = centreline + side * ribbonHalfWidth * width;
  vec3 normal = cross(tangent, width);
  outNormal = length(normal) > 1e-8 ? normalize(normal) : radial;
}
`;

/** The ribbons' material: the standard lit material with its vertices placed by `ribbonVertex`. */
export function ribbonMaterial(uniforms: Record<string, THREE.IUniform>): THREE.MeshStandardMaterial {
  const material = new THREE.MeshStandardMaterial({
    color: 0xffffff,
    vertexColors: true,
    side: THREE.DoubleSide,
    // Curling ribbon is a glossy film.
    roughness: 0.35,
    metalness: 0.05,
  });
  material.onBeforeCompile = (shader) => {
    Object.assign(shader.uniforms, uniforms);
    shader.vertexShader = shader.vertexShader
      .replace("#include <common>", `#include <common>\n${VERTEX_HEAD}`)
      .replace("#include <beginnormal_vertex>", "vec3 ribbonPosition;\nvec3 objectNormal;\nribbonVertex(ribbonPosition, objectNormal);")
      .replace("#include <begin_vertex>", "vec3 transformed = ribbonPosition;");
  };
  material.customProgramCacheKey = () => "up-ribbons";
  return material;
}

/** Length of each ribbon along its points, m (`offsets` as in `RibbonTables`). */
export function ribbonLengths(points: Float32Array, offsets: Uint32Array): Float32Array {
  const n = Math.max(0, offsets.length - 1);
  const lengths = new Float32Array(n);
  for (let r = 0; r < n; r++) {
    let sum = 0;
    for (let i = offsets[r] + 1; i < offsets[r + 1]; i++) {
      const a = (i - 1) * RIBBON_POINT_STRIDE;
      const b = i * RIBBON_POINT_STRIDE;
      if (b + 2 >= points.length) break;
      sum += Math.hypot(points[b] - points[a], points[b + 1] - points[a + 1], points[b + 2] - points[a + 2]);
    }
    lengths[r] = sum;
  }
  return lengths;
}

/**
 * Writes the points, blended from `prev` to `curr` by `alpha`, into `out` as
 * RGBA texels (the fourth float unused): `count` points.
 */
export function writeRibbonTexels(out: Float32Array, prev: Float32Array, curr: Float32Array, count: number, alpha: number): void {
  const a = Math.min(1, Math.max(0, alpha));
  const b = 1 - a;
  const blend = prev.length === curr.length && a < 1;
  for (let i = 0; i < count; i++) {
    const o = i * RIBBON_POINT_STRIDE;
    const t = i * 4;
    if (blend) {
      out[t] = prev[o] * b + curr[o] * a;
      out[t + 1] = prev[o + 1] * b + curr[o + 1] * a;
      out[t + 2] = prev[o + 2] * b + curr[o + 2] * a;
    } else {
      out[t] = curr[o];
      out[t + 1] = curr[o + 1];
      out[t + 2] = curr[o + 2];
    }
  }
}

export class Ribbons {
  /** The ribbons and their weights: what the scene shows. */
  readonly group = new THREE.Group();
  readonly mesh: THREE.Mesh<THREE.InstancedBufferGeometry, THREE.MeshStandardMaterial>;
  /** One ball per weighted ribbon, at its free end. */
  weights: THREE.InstancedMesh;
  /** The free end's point (in all the points) of each weighted ribbon, in instance order. */
  private weightEnds = new Uint32Array(0);
  private readonly weightMatrix = new THREE.Matrix4();
  private texture: THREE.DataTexture;
  private readonly uniforms: Record<string, THREE.IUniform>;
  private pointCapacity = 0;
  /** Points drawn now. */
  private points = 0;
  private readonly color = new THREE.Color();

  constructor(ribbonWidth: number, private readonly weightRadius: number) {
    this.texture = this.makeTexture(TEXTURE_WIDTH);
    this.uniforms = {
      ribbonPoints: { value: this.texture },
      ribbonTextureWidth: { value: TEXTURE_WIDTH },
      ribbonHalfWidth: { value: ribbonWidth / 2 },
    };
    this.mesh = new THREE.Mesh(stripTemplate(), ribbonMaterial(this.uniforms));
    this.mesh.name = "ribbons";
    this.mesh.receiveShadow = true;
    // Placed by the shader: the template's bounds say nothing of where they are.
    this.mesh.frustumCulled = false;
    this.mesh.visible = false;
    this.weights = this.makeWeights(16);
    this.group.name = "ribbons";
    this.group.add(this.mesh);
  }

  private makeWeights(capacity: number): THREE.InstancedMesh {
    if (this.weights) {
      this.group.remove(this.weights);
      this.weights.dispose();
    }
    const ball = new THREE.IcosahedronGeometry(this.weightRadius, 2);
    // Foil: metallic, a little rough.
    const foil = new THREE.MeshStandardMaterial({ color: 0xffffff, metalness: 0.85, roughness: 0.3 });
    const mesh = new THREE.InstancedMesh(ball, foil, capacity);
    mesh.name = "ribbon weights";
    mesh.castShadow = true;
    mesh.frustumCulled = false;
    mesh.count = 0;
    mesh.instanceMatrix.setUsage(THREE.DynamicDrawUsage);
    this.group.add(mesh);
    return mesh;
  }

  private makeTexture(points: number): THREE.DataTexture {
    const rows = Math.max(1, Math.ceil(points / TEXTURE_WIDTH));
    const data = new Float32Array(rows * TEXTURE_WIDTH * 4);
    const texture = new THREE.DataTexture(data, TEXTURE_WIDTH, rows, THREE.RGBAFormat, THREE.FloatType);
    texture.minFilter = THREE.NearestFilter;
    texture.magFilter = THREE.NearestFilter;
    texture.generateMipmaps = false;
    texture.needsUpdate = true;
    this.pointCapacity = rows * TEXTURE_WIDTH;
    return texture;
  }

  /** Ribbons drawn now. */
  get count(): number {
    return this.mesh.geometry.instanceCount;
  }

  /** New ribbons (added, removed or re-tied): their places in the points, lengths from `points`, colours. */
  setRibbons(tables: RibbonTables, points: Float32Array): void {
    const n = tables.bodies.length;
    const total = tables.offsets[n] ?? 0;
    if (total > this.pointCapacity) {
      this.texture.dispose();
      this.texture = this.makeTexture(Math.max(total, this.pointCapacity * 2));
      this.uniforms.ribbonPoints.value = this.texture;
    }
    const lengths = ribbonLengths(points, tables.offsets);
    const ribbon = new Float32Array(n * 4);
    const colors = new Float32Array(n * 3);
    for (let r = 0; r < n; r++) {
      ribbon[r * 4] = tables.offsets[r];
      ribbon[r * 4 + 1] = tables.offsets[r + 1] - tables.offsets[r];
      ribbon[r * 4 + 2] = lengths[r];
      // A phase per ribbon, so that neighbours do not twist in step (golden angle).
      ribbon[r * 4 + 3] = (r * 2.39996) % (2 * Math.PI);
      // 0xRRGGBB is display sRGB; the shader works in linear.
      this.color.setHex(tables.colors[r], THREE.SRGBColorSpace);
      colors[r * 3] = this.color.r;
      colors[r * 3 + 1] = this.color.g;
      colors[r * 3 + 2] = this.color.b;
    }
    const g = this.mesh.geometry;
    g.setAttribute("ribbon", new THREE.InstancedBufferAttribute(ribbon, 4));
    g.setAttribute("color", new THREE.InstancedBufferAttribute(colors, 3));
    g.instanceCount = n;
    this.points = total;
    this.mesh.visible = n > 0;
    const weighted: number[] = [];
    for (let r = 0; r < n; r++) if ((tables.weights[r] ?? 0) > 0) weighted.push(r);
    if (weighted.length > this.weights.instanceMatrix.count) this.weights = this.makeWeights(Math.max(weighted.length, 2 * this.weights.instanceMatrix.count));
    this.weightEnds = Uint32Array.from(weighted, (r) => tables.offsets[r + 1] - 1);
    weighted.forEach((r, k) => this.weights.setColorAt(k, this.color.setHex(tables.colors[r], THREE.SRGBColorSpace)));
    if (this.weights.instanceColor) this.weights.instanceColor.needsUpdate = true;
    this.weights.count = weighted.length;
  }

  /** The frame's points, interpolated by `alpha` between its two steps, into the texture. */
  update(prev: Float32Array, curr: Float32Array, alpha: number): void {
    const count = Math.min(this.points, Math.floor(curr.length / RIBBON_POINT_STRIDE), this.pointCapacity);
    if (count === 0) return;
    const texels = this.texture.image.data as Float32Array;
    writeRibbonTexels(texels, prev, curr, count, alpha);
    this.texture.needsUpdate = true;
    const ends = this.weightEnds;
    for (let k = 0; k < ends.length; k++) {
      const t = ends[k] * 4;
      // The end point is the centre of the weight's collision sphere.
      this.weightMatrix.makeTranslation(texels[t], texels[t + 1], texels[t + 2]);
      this.weights.setMatrixAt(k, this.weightMatrix);
    }
    if (ends.length > 0) this.weights.instanceMatrix.needsUpdate = true;
  }
}
