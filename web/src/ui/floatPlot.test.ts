import { describe, expect, it } from "vitest";
import { FloatSeries, MAX_SAMPLES, axisSpan, spanLabel, toPixel } from "./floatPlot";

const sample = (t: number, ceiling = 1) => ({ t, ceiling, hovering: 1 - ceiling, floor: 0 });

describe("the float plot's scales", () => {
  it("snaps the time axis to the first round span that holds the samples", () => {
    expect(axisSpan(0)).toBe(60);
    expect(axisSpan(60)).toBe(60);
    expect(axisSpan(61)).toBe(300);
    expect(axisSpan(3599)).toBe(3600);
    expect(axisSpan(5 * 3600)).toBe(6 * 3600);
    expect(axisSpan(47 * 3600)).toBe(48 * 3600);
    expect(axisSpan(50 * 3600)).toBe(3 * 86_400);
    expect([60, 900, 3600, 12 * 3600, 3 * 86_400].map(spanLabel)).toEqual(["1 min", "15 min", "1 h", "12 h", "3 d"]);
  });

  it("maps time left to right and the share bottom to top, clamped into the area", () => {
    const area = { left: 10, top: 20, width: 200, height: 100 };
    expect(toPixel(area, 3600, 0, 0)).toEqual([10, 120]);
    expect(toPixel(area, 3600, 3600, 1)).toEqual([210, 20]);
    expect(toPixel(area, 3600, 1800, 0.25)).toEqual([110, 95]);
    expect(toPixel(area, 3600, 7200, 2)).toEqual([210, 20]);
    expect(toPixel(area, 3600, -5, -1)).toEqual([10, 120]);
  });
});

describe("the float series", () => {
  it("keeps samples in time order and starts afresh with a new world", () => {
    const series = new FloatSeries();
    series.push(sample(0));
    series.push(sample(60));
    series.push(sample(120, 0.5));
    expect(series.samples.map((s) => s.t)).toEqual([0, 60, 120]);
    series.push(sample(1));
    expect(series.samples.map((s) => s.t)).toEqual([1]);
  });

  it("thins itself past MAX_SAMPLES, keeping the first and the newest", () => {
    const series = new FloatSeries();
    const n = MAX_SAMPLES * 3;
    for (let i = 0; i < n; i++) series.push(sample(i * 60, 1 - i / n));
    expect(series.samples.length).toBeLessThanOrEqual(MAX_SAMPLES);
    expect(series.samples.length).toBeGreaterThan(MAX_SAMPLES / 4);
    expect(series.samples[0].t).toBe(0);
    expect(series.samples[series.samples.length - 1].t).toBe((n - 1) * 60);
    for (let i = 1; i < series.samples.length; i++) expect(series.samples[i].t).toBeGreaterThan(series.samples[i - 1].t);
  });
});
