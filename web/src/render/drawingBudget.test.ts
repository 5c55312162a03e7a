import { describe, expect, it } from "vitest";
import { CrowdGovernor, FULL_BUDGET, JUDGED_FRAMES, LIGHT_BUDGET, SLOW_FRAME_MS, STALL_MS, WARMUP_FRAMES, costText, drawingBudget } from "./drawingBudget";

describe("the drawing budget", () => {
  it("draws for less on a phone and a tablet, in full on a desktop and a touch laptop's big screen", () => {
    expect(drawingBudget({ coarsePointer: true, screenShortSide: 390 })).toEqual(LIGHT_BUDGET);
    expect(drawingBudget({ coarsePointer: true, screenShortSide: 768 })).toEqual(LIGHT_BUDGET);
    expect(drawingBudget({ coarsePointer: false, screenShortSide: 390 })).toEqual(FULL_BUDGET);
    expect(drawingBudget({ coarsePointer: true, screenShortSide: 1200 })).toEqual(FULL_BUDGET);
  });

  it("spends less on every count: shadow texels, pixels and the crowd mesh's start", () => {
    expect(LIGHT_BUDGET.shadowMapSize ** 2).toBeLessThan(FULL_BUDGET.shadowMapSize ** 2);
    expect(LIGHT_BUDGET.pixelRatioCap).toBeLessThan(FULL_BUDGET.pixelRatioCap);
    expect(LIGHT_BUDGET.crowdAbove).toBeLessThan(FULL_BUDGET.crowdAbove);
  });

  it("says what it leaves out, and nothing on the full budget", () => {
    expect(costText(FULL_BUDGET)).toBeNull();
    expect(costText({ ...LIGHT_BUDGET, crowdAbove: 49 })).toBe(`Drawing for less: shadows ${LIGHT_BUDGET.shadowMapSize}², ≤ 1.5 px/px, simple balloons above 49`);
  });

  it("gives a fresh budget each time (the page lowers its own copy)", () => {
    const b = drawingBudget({ coarsePointer: true, screenShortSide: 390 });
    b.crowdAbove = 3;
    expect(LIGHT_BUDGET.crowdAbove).not.toBe(3);
  });
});

describe("the crowd governor", () => {
  /** Feeds `n` frames of `ms` with `count` balloons; the last non-null answer. */
  function feed(g: CrowdGovernor, n: number, ms: number, count: number): number | null {
    let answer: number | null = null;
    for (let i = 0; i < n; i++) answer = g.frame(ms, count) ?? answer;
    return answer;
  }

  it("lowers the crowd count to under the balloons shown when frames are slow", () => {
    const g = new CrowdGovernor(150);
    expect(feed(g, WARMUP_FRAMES + JUDGED_FRAMES, SLOW_FRAME_MS * 1.5, 50)).toBe(49);
    expect(g.crowdAbove).toBe(49);
  });

  it("leaves it while frames keep pace, during the warm-up, and over stalls", () => {
    const g = new CrowdGovernor(150);
    expect(feed(g, WARMUP_FRAMES, 500, 50)).toBeNull();
    expect(feed(g, 5 * JUDGED_FRAMES, 16.7, 50)).toBeNull();
    expect(feed(g, 5 * JUDGED_FRAMES, STALL_MS + 1, 50)).toBeNull();
    expect(g.crowdAbove).toBe(150);
  });

  it("judges only frames drawn with the full mesh, and never raises the count", () => {
    const g = new CrowdGovernor(150);
    // Above the count the crowd mesh already draws them: slow frames there say nothing about the full mesh.
    expect(feed(g, WARMUP_FRAMES + 3 * JUDGED_FRAMES, 100, 400)).toBeNull();
    expect(feed(g, JUDGED_FRAMES, 100, 120)).toBe(119);
    expect(feed(g, 3 * JUDGED_FRAMES, 100, 300)).toBeNull();
    expect(g.crowdAbove).toBe(119);
  });
});
