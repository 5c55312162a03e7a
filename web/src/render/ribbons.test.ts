import { describe, expect, it } from "vitest";
import * as THREE from "three";
import { CURL_SAMPLES, Ribbons, STRIP_SAMPLES, TEXTURE_WIDTH, ribbonLengths, stripTemplate, writeRibbonTexels } from "./ribbons";
import type { RibbonTables } from "../sim/engine";
import { RIBBON_POINT_STRIDE } from "../sim/frameLayout";

/** `n` ribbons of `points` points hanging straight down, 0.1 m a segment, side by side; every third weighted when `weighted`. */
function hanging(n: number, points: number, weighted = false): { tables: RibbonTables; curr: Float32Array } {
  const curr = new Float32Array(n * points * 3);
  const offsets = new Uint32Array(n + 1);
  for (let r = 0; r < n; r++) {
    offsets[r] = r * points;
    for (let i = 0; i < points; i++) curr.set([r * 0.01, 2.5 - 0.1 * i, 0], (r * points + i) * 3);
  }
  offsets[n] = n * points;
  const bodies = Uint32Array.from({ length: n }, (_, r) => n - 1 - r);
  const colors = Uint32Array.from({ length: n }, (_, r) => (r % 2 ? 0xff0000 : 0x00ff00));
  const weights = Float32Array.from({ length: n }, (_, r) => (weighted && r % 3 === 0 ? 0.01 : 0));
  return { tables: { offsets, bodies, colors, weights }, curr };
}

describe("ribbon strips", () => {
  it("draw every ribbon from one strip of two vertices a sample", () => {
    const g = stripTemplate();
    const samples = STRIP_SAMPLES + CURL_SAMPLES + 1;
    expect(g.getAttribute("position").count).toBe(2 * samples);
    expect(g.getIndex()!.count).toBe(6 * (samples - 1));
    const p = g.getAttribute("position");
    expect([p.getX(0), p.getY(0), p.getX(2 * samples - 1), p.getY(2 * samples - 1)]).toEqual([0, -1, samples - 1, 1]);
  });

  it("measure each ribbon's length along its points", () => {
    const points = new Float32Array([0, 0, 0, 3, 4, 0, 3, 4, 1, 9, 9, 9, 9, 9, 8]);
    expect(Array.from(ribbonLengths(points, new Uint32Array([0, 3, 5])))).toEqual([6, 1]);
  });

  it("blend the two steps' points into RGBA texels", () => {
    const prev = new Float32Array([0, 0, 0, 2, 2, 2]);
    const curr = new Float32Array([1, 2, 3, 4, 4, 4]);
    const out = new Float32Array(8);
    writeRibbonTexels(out, prev, curr, 2, 0.5);
    expect(Array.from(out)).toEqual([0.5, 1, 1.5, 0, 3, 3, 3, 0]);
    // Different lengths (ribbons re-tied between the steps): the current points.
    writeRibbonTexels(out, new Float32Array(3), curr, 2, 0.25);
    expect(Array.from(out)).toEqual([1, 2, 3, 0, 4, 4, 4, 0]);
  });

  it("place each ribbon by its first point, point count, length and colour", () => {
    const ribbons = new Ribbons(0.005, 0.025);
    const { tables, curr } = hanging(3, 5, true);
    ribbons.setRibbons(tables, curr);
    expect(ribbons.count).toBe(3);
    expect(ribbons.mesh.visible).toBe(true);
    const a = ribbons.mesh.geometry.getAttribute("ribbon") as THREE.InstancedBufferAttribute;
    expect([a.getX(1), a.getY(1)]).toEqual([5, 5]);
    expect(a.getZ(1)).toBeCloseTo(0.4, 5);
    const c = ribbons.mesh.geometry.getAttribute("color") as THREE.InstancedBufferAttribute;
    // 0xff0000 in sRGB is (1, 0, 0) in linear too; 0x00ff00 is (0, 1, 0).
    expect([c.getX(1), c.getY(1), c.getZ(1)]).toEqual([1, 0, 0]);
    expect([c.getX(0), c.getY(0), c.getZ(0)]).toEqual([0, 1, 0]);
    ribbons.update(curr, curr, 1);
    // Ribbon 0 has a weight (every third): one ball, at its free end.
    expect(ribbons.weights.count).toBe(1);
    const m = new THREE.Matrix4();
    ribbons.weights.getMatrixAt(0, m);
    expect(new THREE.Vector3().setFromMatrixPosition(m).toArray()).toEqual([0, curr[13], 0]);
    const texture = ribbons.mesh.material as THREE.MeshStandardMaterial;
    expect(texture.side).toBe(THREE.DoubleSide);
    ribbons.setRibbons({ offsets: new Uint32Array(1), bodies: new Uint32Array(0), colors: new Uint32Array(0), weights: new Float32Array(0) }, new Float32Array(0));
    expect(ribbons.weights.count).toBe(0);
    expect(ribbons.count).toBe(0);
    expect(ribbons.mesh.visible).toBe(false);
  });

  it("updates 5,000 ribbons' 85,000 points, each between its two steps", () => {
    const n = 5000;
    const points = 17; // 16 segments, the scenes' default; no weights, as there
    const { tables, curr } = hanging(n, points);
    const prev = curr.map((v) => v + 0.001);
    const ribbons = new Ribbons(0.005, 0.025);
    // New ribbons (added, popped, re-tied): the third of three, warm.
    let setMs = 0;
    for (let k = 0; k < 3; k++) {
      const t0 = performance.now();
      ribbons.setRibbons(tables, curr);
      setMs = performance.now() - t0;
    }
    expect(ribbons.count).toBe(n);
    const times: number[] = [];
    for (let k = 0; k < 30; k++) {
      const start = performance.now();
      ribbons.update(prev, curr, k / 30);
      times.push(performance.now() - start);
    }
    // Every point is where the last frame (alpha 29/30) puts it.
    const texels = (ribbons as unknown as { texture: THREE.DataTexture }).texture.image.data as Float32Array;
    const alpha = 29 / 30;
    let worst = 0;
    for (let i = 0; i < n * points; i++) {
      for (let axis = 0; axis < 3; axis++) {
        const o = i * RIBBON_POINT_STRIDE + axis;
        const expected = prev[o] * (1 - alpha) + curr[o] * alpha;
        worst = Math.max(worst, Math.abs(texels[i * 4 + axis] - expected));
      }
    }
    // Within the texture's float32 rounding of points about 2 m out.
    expect(worst).toBeLessThan(1e-5);
    // Its time is reported, not asserted (a shared machine's load decides
    // it; `make measure` times the page's frames).
    times.sort((x, y) => x - y);
    console.log(
      `ribbons: ${n} ribbons of ${points} points (${Math.ceil((n * points) / TEXTURE_WIDTH)} texture rows): ` +
        `update median ${times[times.length >> 1].toFixed(2)} ms, worst ${times[times.length - 1].toFixed(2)} ms; ` +
        `new ribbons ${setMs.toFixed(1)} ms`,
    );
  });

});
