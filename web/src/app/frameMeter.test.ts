import { describe, expect, it } from "vitest";
import { FrameMeter, quantile } from "./frameMeter";

describe("FrameMeter", () => {
  it("summarises the frames recorded: median, p95, mean and max of each part", () => {
    const meter = new FrameMeter(1000);
    // Work 1..100 ms in a shuffled order, render ten times less.
    const values = Array.from({ length: 100 }, (_, i) => ((i * 37) % 100) + 1);
    for (const v of values) meter.record(v, v / 10);
    const s = meter.summary();
    expect(s.n).toBe(100);
    expect(s.work).toEqual({ median: 50, p95: 95, mean: 50.5, max: 100 });
    expect(s.render?.median).toBeCloseTo(5, 12);
    expect(s.render?.max).toBeCloseTo(10, 12);
  });

  it("keeps the newest frames when the ring is full, oldest first", () => {
    const meter = new FrameMeter(4);
    for (let i = 1; i <= 10; i++) meter.record(i, 0);
    expect(Array.from(meter.samples().work)).toEqual([7, 8, 9, 10]);
    expect(meter.summary().work?.mean).toBe(8.5);
  });

  it("starts afresh after a reset, and says so when nothing was recorded", () => {
    const meter = new FrameMeter(8);
    meter.record(3, 1);
    meter.reset();
    expect(meter.summary()).toEqual({ n: 0, work: null, render: null });
    meter.record(2, 1);
    expect(Array.from(meter.samples().work)).toEqual([2]);
  });

  it("sorts numerically, not as text (9 < 10)", () => {
    const meter = new FrameMeter(8);
    for (const v of [10, 9, 100]) meter.record(v, 0);
    expect(meter.summary().work?.median).toBe(10);
  });
});

describe("quantile", () => {
  it("takes the nearest rank, clamped to the samples", () => {
    const s = [1, 2, 3, 4];
    expect(quantile(s, 0)).toBe(1);
    expect(quantile(s, 0.5)).toBe(2);
    expect(quantile(s, 0.76)).toBe(4);
    expect(quantile(s, 2)).toBe(4);
  });
});
