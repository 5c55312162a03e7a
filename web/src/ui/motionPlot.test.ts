import { describe, expect, it } from "vitest";
import { SampleRing, WINDOW_S, extent, timeRange, timeText, valueRange } from "./motionPlot";

describe("the motion plot's ring buffer", () => {
  it("keeps samples oldest first and overwrites the oldest when full", () => {
    const ring = new SampleRing(4);
    for (let i = 0; i < 6; i++) ring.push(i, 10 + i, -i);
    expect(ring.length).toBe(4);
    expect([0, 1, 2, 3].map((i) => ring.get(i, 0))).toEqual([2, 3, 4, 5]);
    expect(ring.get(0, 1)).toBe(12);
    expect(ring.get(3, 2)).toBe(-5);
    expect(ring.lastTime()).toBe(5);
    ring.clear();
    expect(ring.length).toBe(0);
    expect(ring.lastTime()).toBeNaN();
  });

  it("measures the extent of a field from a time on", () => {
    const ring = new SampleRing(8);
    [
      [0, 5, -3],
      [1, 1, 0.5],
      [2, 2, 0.2],
    ].forEach(([t, h, v]) => ring.push(t, h, v));
    expect(extent(ring, 1, 0)).toEqual([1, 5]);
    expect(extent(ring, 2, 1)).toEqual([0.2, 0.5]);
  });
});

describe("the motion plot's axes", () => {
  it("shows the last window of time, from the first sample while there are fewer", () => {
    expect(timeRange(2, 5)).toEqual([2, 2 + WINDOW_S]);
    expect(timeRange(0, 100)).toEqual([100 - WINDOW_S, 100]);
    expect(timeRange(NaN, NaN)).toEqual([0, WINDOW_S]);
  });

  it("holds every value with a margin, its ends on round steps", () => {
    const r = valueRange(0.13, 2.87, 0.2);
    expect(r.low).toBeLessThanOrEqual(0.13);
    expect(r.high).toBeGreaterThanOrEqual(2.87);
    expect([0.1, 0.2, 0.5, 1, 2, 5]).toContain(r.step);
    expect(Math.abs(r.low / r.step - Math.round(r.low / r.step))).toBeLessThan(1e-9);
    expect(Math.abs(r.high / r.step - Math.round(r.high / r.step))).toBeLessThan(1e-9);
  });

  it("is at least the smallest span wide around a constant, and copes with no samples", () => {
    const r = valueRange(1.5, 1.5, 0.2);
    expect(r.high - r.low).toBeGreaterThanOrEqual(0.2);
    expect(r.low).toBeLessThan(1.5);
    expect(r.high).toBeGreaterThan(1.5);
    const empty = valueRange(Infinity, -Infinity, 0.2);
    expect(empty.low).toBeLessThanOrEqual(0);
    expect(empty.high).toBeGreaterThanOrEqual(0);
  });

  it("holds a negative terminal speed below the samples", () => {
    const r = valueRange(-0.9, 0.05, 0.2);
    expect(r.low).toBeLessThanOrEqual(-0.9);
    expect(r.high).toBeGreaterThanOrEqual(0.05);
  });
});

describe("the motion plot's time labels", () => {
  it("switch from seconds to minutes to hours", () => {
    expect(timeText(42)).toBe("42 s");
    expect(timeText(900)).toBe("15 min");
    expect(timeText(5400 * 10)).toBe("15.0 h");
  });
});
