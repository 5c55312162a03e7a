import { describe, expect, it } from "vitest";
import { SQUASH_MIN_DRAWN_M, SQUASH_RETURN_S, SquashDents, springBack } from "./squash";

/** One body's dent row: normal (unit) times depth, and the reach. */
function table(...rows: [number, number, number, number][]): Float32Array {
  return Float32Array.from(rows.flat());
}

describe("squash spring-back", () => {
  it("decays exponentially with the dent's age, whatever the frame rate", () => {
    expect(springBack(0.014, 0)).toBeCloseTo(0.014, 9);
    expect(springBack(0.014, SQUASH_RETURN_S)).toBeCloseTo(0.014 / Math.E, 9);
    // A function of the age alone: drawing at 30 or 144 fps reads the same depth at the same moment.
    const at = (fps: number) => {
      let t = 0;
      let d = 0;
      while (t < 0.05 - 1e-12) {
        t += 1 / fps;
        d = springBack(0.014, Math.min(t, 0.05));
      }
      return d;
    };
    expect(at(30)).toBeCloseTo(at(144), 12);
    // Gone (exactly zero) once under the drawn threshold: a 1.4 cm dent after ≈ 4 τ.
    const gone = SQUASH_RETURN_S * Math.log(0.014 / SQUASH_MIN_DRAWN_M);
    expect(springBack(0.014, gone * 0.99)).toBeGreaterThan(0);
    expect(springBack(0.014, gone * 1.01)).toBe(0);
    expect(springBack(0.014, -1)).toBeCloseTo(0.014, 9);
  });

  it("keeps each body's deepest dent still showing and writes it as normal × depth", () => {
    const dents = new SquashDents();
    dents.reset(3);
    const out = new Float32Array(12);
    // Body 1 hits a wall along +x: 1.4 cm, its contact 0.14 m out.
    dents.add(table([0, 0, 0, 0], [0.014, 0, 0, 0.14], [0, 0, 0, 0]), 1000);
    expect(dents.write(out, 1000)).toBe(1);
    expect(Array.from(out.slice(4, 8)).map((v) => +v.toFixed(6))).toEqual([0.014, 0, 0, 0.14]);
    expect(Array.from(out.slice(0, 4))).toEqual([0, 0, 0, 0]);
    // A shallower dent 10 ms later does not replace what is left of the deep one.
    dents.add(table([0, 0, 0, 0], [0, 0.002, 0, 0.1], [0, 0, 0, 0]), 1010);
    dents.write(out, 1010);
    expect(out[4]).toBeCloseTo(springBack(0.014, 0.01), 6);
    expect(out[5]).toBe(0);
    // Once it has sprung back, a new one does.
    dents.add(table([0, 0, 0, 0], [0, -0.005, 0, 0.12], [0, 0, 0, 0]), 1200);
    dents.write(out, 1200);
    expect(Array.from(out.slice(4, 8)).map((v) => +v.toFixed(6))).toEqual([0, -0.005, 0, 0.12]);
    // And it springs back to exactly round.
    expect(dents.write(out, 1200 + 1000 * SQUASH_RETURN_S * 20)).toBe(0);
    expect(Array.from(out)).toEqual(Array(12).fill(0));
  });

  it("forgets every dent when the bodies change", () => {
    const dents = new SquashDents();
    dents.reset(1);
    dents.add(table([0, 0, 0.02, 0.14]), 0);
    dents.reset(2);
    const out = new Float32Array(8).fill(9);
    expect(dents.write(out, 0)).toBe(0);
    expect(Array.from(out)).toEqual(Array(8).fill(0));
  });

  it("keeps the deepest dent taken as the peak, after a shallower bounce replaced it and after it sprang back", () => {
    const dents = new SquashDents();
    dents.reset(1);
    dents.add(table([0.01, 0, 0, 0.14]), 1000);
    // Four steps on, the first dent has sprung back below the bounce's 4.5 mm: the bounce shows.
    dents.add(table([0.0045, 0, 0, 0.14]), 1067);
    expect(dents.madeAt(0)).toBe(1067);
    const peak = dents.peak(0, [0, 1000]);
    expect(peak.madeAt).toBe(1000);
    expect(peak.at[0][0]).toBeCloseTo(0.01, 6);
    expect(peak.at[0][3]).toBeCloseTo(0.14, 6);
    expect(peak.at[1]).toEqual([0, 0, 0, 0]);
    dents.write(new Float32Array(4), 5000);
    expect(dents.madeAt(0)).toBeNull();
    expect(dents.peak(0, []).madeAt).toBe(1000);
    dents.reset(1);
    expect(dents.peak(0, [0])).toEqual({ at: [[0, 0, 0, 0]], madeAt: null });
  });
});
