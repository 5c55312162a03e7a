// Procedural normal maps: a height field over the unit square turned into a
// tangent-space normal texture, and the seeded random numbers the fields use
// (latex pleats and creases in finishes.ts, the foil's crimps in foilBalloons.ts).

import * as THREE from "three";

/** A deterministic pseudo-random sequence in [0, 1) (mulberry32): the same map every load. */
export function seededRandom(seed: number): () => number {
  let a = seed >>> 0;
  return () => {
    a = (a + 0x6d2b79f5) >>> 0;
    let t = a;
    t = Math.imul(t ^ (t >>> 15), t | 1);
    t ^= t + Math.imul(t ^ (t >>> 7), t | 61);
    return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
  };
}

/**
 * An `n`×`n` tangent-space normal map from a height field `height(u, v)` over
 * the unit square, by central differences; `periodicU` wraps u (the seam
 * around a balloon), else the field's edges are clamped.
 */
export function normalMapFromHeight(height: (u: number, v: number) => number, strength: number, n: number, periodicU = true): THREE.DataTexture {
  const h = new Float32Array(n * n);
  for (let j = 0; j < n; j++) for (let i = 0; i < n; i++) h[j * n + i] = height((i + 0.5) / n, (j + 0.5) / n);
  const column = periodicU ? (i: number) => ((i % n) + n) % n : (i: number) => Math.min(n - 1, Math.max(0, i));
  const at = (i: number, j: number) => h[Math.min(n - 1, Math.max(0, j)) * n + column(i)];
  const data = new Uint8Array(n * n * 4);
  for (let j = 0; j < n; j++) {
    for (let i = 0; i < n; i++) {
      const dx = (at(i + 1, j) - at(i - 1, j)) * strength;
      const dy = (at(i, j + 1) - at(i, j - 1)) * strength;
      const len = Math.hypot(dx, dy, 1);
      const o = (j * n + i) * 4;
      data[o] = Math.round(((-dx / len) * 0.5 + 0.5) * 255);
      data[o + 1] = Math.round(((-dy / len) * 0.5 + 0.5) * 255);
      data[o + 2] = Math.round(((1 / len) * 0.5 + 0.5) * 255);
      data[o + 3] = 255;
    }
  }
  const texture = new THREE.DataTexture(data, n, n, THREE.RGBAFormat);
  texture.wrapS = periodicU ? THREE.RepeatWrapping : THREE.ClampToEdgeWrapping;
  texture.wrapT = THREE.ClampToEdgeWrapping;
  texture.magFilter = THREE.LinearFilter;
  texture.minFilter = THREE.LinearMipmapLinearFilter;
  texture.generateMipmaps = true;
  texture.needsUpdate = true;
  return texture;
}
