import { describe, expect, it } from "vitest";
import { FORCE_FLOATS, ForceProbe, PROBE_ALL, checkForceLayout, PROBE_OFF, findForceRow, forceRowCount, netForce, readForceRow, type ForceSource } from "./forcesFrame";
import type { BodyCard } from "./engine";

/** A row as the engine writes it: index, six forces, centre of mass, centre of buoyancy, knot. */
function row(index: number, knot: [number, number, number] | null = null): number[] {
  const r = [index];
  for (let k = 0; k < 6; k++) r.push(index + k + 0.1, -(k + 1), k * 0.5);
  r.push(1, 2, 3, 1, 2.1, 3, ...(knot ?? [NaN, NaN, NaN]));
  return r;
}

describe("force rows", () => {
  it("reads each force, the centres and the knot where the engine writes them", () => {
    const rows = new Float32Array([...row(4), ...row(7, [1, 1.5, 3])]);
    expect(rows.length).toBe(2 * FORCE_FLOATS);
    expect(forceRowCount(rows)).toBe(2);
    const a = readForceRow(rows, 0);
    expect(a.index).toBe(4);
    expect(a.forces.weight[0]).toBeCloseTo(4.1, 5);
    expect(a.forces.buoyancy[1]).toBe(-2);
    expect(a.forces.other).toEqual([4 + 5 + 0.1, -6, 2.5].map((v) => Math.fround(v)));
    expect(a.centerOfMass).toEqual([1, 2, 3]);
    expect(a.centerOfBuoyancy[1]).toBeCloseTo(2.1, 5);
    expect(a.knot).toBeNull();
    expect(findForceRow(rows, 7)?.knot).toEqual([1, 1.5, 3]);
    expect(findForceRow(rows, 5)).toBeNull();
  });

  it("sums the forces", () => {
    const r = readForceRow(new Float32Array(row(0)), 0);
    const net = netForce(r);
    expect(net[1]).toBe(-(1 + 2 + 3 + 4 + 5 + 6));
    expect(net[2]).toBeCloseTo(0.5 * (0 + 1 + 2 + 3 + 4 + 5), 5);
  });
});

/** An engine that records what it is told and writes the rows it is given. */
class FakeEngine implements ForceSource {
  told: number[] = [];
  rows = new Float32Array(0);
  count = 5;
  setForceProbe(which: number): void {
    this.told.push(which);
  }
  forces(): Float32Array {
    return this.rows;
  }
  bodyCard(index: number): BodyCard {
    return { index, gas: "helium" } as BodyCard;
  }
  bodyCount(): number {
    return this.count;
  }
}

describe("the worker's force probe", () => {
  it("tells the engine only what changed, and nothing while nothing is asked", () => {
    const probe = new ForceProbe();
    const engine = new FakeEngine();
    expect(probe.collect(engine)).toBeNull();
    probe.apply(engine);
    probe.apply(engine);
    expect(engine.told).toEqual([PROBE_OFF]);
    probe.select(3);
    probe.apply(engine);
    probe.setAll(true);
    probe.apply(engine);
    probe.setAll(false);
    probe.select(-1);
    probe.apply(engine);
    expect(engine.told).toEqual([PROBE_OFF, 3, PROBE_ALL, PROBE_OFF]);
  });

  it("follows the selected body to where the engine's row says it is, and sends its card", () => {
    const probe = new ForceProbe();
    const engine = new FakeEngine();
    probe.select(4);
    probe.apply(engine);
    // Before a step the engine has recorded nothing: the selection stands.
    let payload = probe.collect(engine)!;
    expect(payload.selected).toBe(4);
    expect(payload.card?.index).toBe(4);
    expect(payload.rows.length).toBe(0);
    probe.stepped();
    engine.rows = new Float32Array(row(1));
    payload = probe.collect(engine)!;
    expect(payload.selected).toBe(1);
    expect(payload.card?.index).toBe(1);
    // The rows are a copy: the engine's memory may change under a view.
    engine.rows[0] = 9;
    expect(payload.rows[0]).toBe(1);
    // The same body under its new index: nothing to tell the engine.
    probe.apply(engine);
    expect(engine.told).toEqual([4]);
  });

  it("drops the selection when the body leaves the world", () => {
    const probe = new ForceProbe();
    const engine = new FakeEngine();
    probe.select(2);
    probe.apply(engine);
    probe.stepped();
    engine.rows = new Float32Array(0);
    expect(probe.collect(engine)!.selected).toBe(-1);
  });

  it("keeps the index in step when a balloon is popped (the last takes its place)", () => {
    const probe = new ForceProbe();
    probe.setAll(true);
    probe.select(4);
    probe.removed(1, 5);
    expect(probe.selected).toBe(1);
    probe.removed(0, 4);
    expect(probe.selected).toBe(1);
    probe.removed(1, 3);
    expect(probe.selected).toBe(-1);
  });

  it("forgets the selection and what the engine knew when the world is rebuilt", () => {
    const probe = new ForceProbe();
    const engine = new FakeEngine();
    probe.setAll(true);
    probe.select(1);
    probe.apply(engine);
    probe.worldRebuilt();
    expect(probe.selected).toBe(-1);
    probe.apply(engine);
    expect(engine.told).toEqual([PROBE_ALL, PROBE_ALL]);
  });
});

describe("the force rows' layout", () => {
  it("is checked against the engine's", () => {
    expect(() => checkForceLayout({ force_floats: FORCE_FLOATS })).not.toThrow();
    expect(() => checkForceLayout({ force_floats: FORCE_FLOATS + 3 })).toThrow(/floats per body's forces/);
  });
});
