// The page reads the engine's recorded forces as the engine writes them: the
// row layout, the probe's three settings, a probed body followed by its
// handle, and the card beside the forces. Needs the wasm build.

import { readFileSync } from "node:fs";
import { beforeAll, describe, expect, it } from "vitest";
import { loadBuiltEngine } from "./builtEngine";
import type { Engine } from "./engine";
import { FORCE_FLOATS, PROBE_ALL, PROBE_OFF, checkForceLayout, forceRowCount, netForce, readForceRow } from "./forcesFrame";

let engine: Engine;

beforeAll(async () => {
  engine = await loadBuiltEngine();
});

const twoGases = readFileSync(new URL("../../../assets/scenes/two-gases.json", import.meta.url), "utf8");

describe("the engine's force rows", () => {
  it("have the layout the page reads", () => {
    expect(engine.constants.force_floats).toBe(FORCE_FLOATS);
    expect(() => checkForceLayout(engine.constants)).not.toThrow();
  });

  it("are none while nothing is probed, one per body with all, one with one", () => {
    engine.loadDefaultScene();
    engine.setForceProbe(PROBE_OFF);
    engine.step(2);
    expect(engine.forces().length).toBe(0);
    engine.setForceProbe(PROBE_ALL);
    engine.step(1);
    const all = engine.forces().slice();
    const n = engine.bodyCount();
    expect(forceRowCount(all)).toBe(n);
    expect([...Array(n).keys()].map((i) => all[i * FORCE_FLOATS]).sort((a, b) => a - b)).toEqual([...Array(n).keys()]);
    engine.setForceProbe(3);
    engine.step(1);
    const one = engine.forces();
    expect(one.length).toBe(FORCE_FLOATS);
    expect(one[0]).toBe(3);
  });

  it("give a balloon's weight as m·g down and its card's net lift as buoyancy plus weight", () => {
    engine.loadDefaultScene();
    engine.setForceProbe(0);
    engine.step(1);
    const row = readForceRow(engine.forces(), 0);
    const card = engine.bodyCard(0);
    expect(row.forces.weight[1]).toBeLessThan(0);
    expect(-row.forces.weight[1] / (card.mass_kg * 9.81)).toBeCloseTo(1, 2);
    expect(row.forces.buoyancy[1]).toBeGreaterThan(0);
    expect(row.forces.buoyancy[1] + row.forces.weight[1]).toBeCloseTo(card.net_lift_n, 4);
    expect(card.net_lift_g).toBeCloseTo((card.net_lift_n / 9.81) * 1000, 0);
  });

  it("follow the probed balloon when another is removed and it takes the removed one's place", () => {
    engine.loadDefaultScene();
    const last = engine.bodyCount() - 1;
    engine.setForceProbe(last);
    engine.step(1);
    const before = readForceRow(engine.forces().slice(), 0);
    expect(before.index).toBe(last);
    engine.remove(0);
    engine.step(1);
    const after = readForceRow(engine.forces(), 0);
    expect(after.index).toBe(0);
    // The same balloon: its mass, hence its weight, is the same.
    expect(after.forces.weight[1]).toBeCloseTo(before.forces.weight[1], 6);
  });

  it("show helium lifting and air sinking (two gases)", () => {
    engine.loadSceneJson(twoGases);
    engine.setForceProbe(PROBE_ALL);
    engine.step(1);
    const rows = engine.forces().slice();
    const gases = new Set<string>();
    for (let i = 0; i < forceRowCount(rows); i++) {
      const row = readForceRow(rows, i);
      const card = engine.bodyCard(row.index);
      gases.add(card.gas);
      expect(row.forces.buoyancy[1]).toBeGreaterThan(0);
      const lift = row.forces.buoyancy[1] + row.forces.weight[1];
      if (card.gas === "helium") expect(lift).toBeGreaterThan(0);
      if (card.gas === "air") expect(lift).toBeLessThan(0);
      expect(netForce(row).every(Number.isFinite)).toBe(true);
    }
    expect([...gases].sort()).toEqual(["air", "helium"]);
  });
});
