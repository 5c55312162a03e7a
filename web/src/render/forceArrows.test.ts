import { describe, expect, it } from "vitest";
import { MAX_ARROW_M, MIN_ARROW_M, NEWTONS_PER_METRE, arrowTail, arrowsOfRow, arrowsOfRows } from "./forceArrows";
import { FORCE_FLOATS, readForceRow } from "../sim/forcesFrame";

/** A row of a balloon at rest on its ribbon: weight, buoyancy, ribbon pull; no drag, contact or hand. */
function restingRow(index = 2, knot: number[] = [0.5, 1.0, 0]): Float32Array {
  return new Float32Array([
    index,
    ...[0, -0.055, 0], // weight
    ...[0, 0.135, 0], // buoyancy
    ...[0, 0, 0], // drag
    ...[0, 0, 0], // contact
    ...[0, -0.08, 0], // ribbon
    ...[0, 0, 0], // other
    ...[0.5, 1.2, 0], // centre of mass
    ...[0.5, 1.25, 0], // centre of buoyancy
    ...knot,
  ]);
}

describe("force arrows from a row", () => {
  it("draws each non-zero force from where it acts, its length the force over the scale", () => {
    const arrows = arrowsOfRow(readForceRow(restingRow(), 0));
    expect(arrows.map((a) => a.kind)).toEqual(["weight", "buoyancy", "ribbon"]);
    const [weight, buoyancy, ribbon] = arrows;
    expect(weight.origin).toEqual([0.5, Math.fround(1.2), 0]);
    expect(weight.direction).toEqual([0, -1, 0]);
    expect(weight.length).toBeCloseTo(0.055 / NEWTONS_PER_METRE, 6);
    expect(buoyancy.origin).toEqual([0.5, Math.fround(1.25), 0]);
    expect(buoyancy.direction).toEqual([0, 1, 0]);
    expect(ribbon.origin).toEqual([0.5, 1, 0]);
    expect(ribbon.body).toBe(2);
    // A balloon's weight is a visible arrow beside a 28 cm balloon.
    expect(weight.length).toBeGreaterThan(0.1);
  });

  it("has no ribbon arrow without a knot, and cuts an arrow longer than the longest drawn", () => {
    const rows = restingRow(0, [NaN, NaN, NaN]);
    rows[10] = 3; // contact, x: a hard knock
    const arrows = arrowsOfRow(readForceRow(rows, 0));
    expect(arrows.some((a) => a.kind === "ribbon")).toBe(false);
    const contact = arrows.find((a) => a.kind === "contact")!;
    expect(contact.length).toBe(MAX_ARROW_M);
    expect(contact.clipped).toBe(true);
    expect(contact.force[0]).toBe(3);
    expect(contact.direction).toEqual([1, 0, 0]);
  });

  it("leaves out forces too small to see", () => {
    const rows = restingRow();
    rows[8] = (MIN_ARROW_M / 2) * NEWTONS_PER_METRE; // drag, y
    expect(arrowsOfRow(readForceRow(rows, 0)).some((a) => a.kind === "drag")).toBe(false);
    rows[8] = MIN_ARROW_M * 2 * NEWTONS_PER_METRE;
    expect(arrowsOfRow(readForceRow(rows, 0)).some((a) => a.kind === "drag")).toBe(true);
  });

  it("takes every row, or only the selected body's", () => {
    const two = new Float32Array(2 * FORCE_FLOATS);
    two.set(restingRow(2), 0);
    two.set(restingRow(5), FORCE_FLOATS);
    expect(arrowsOfRows(two).length).toBe(6);
    expect(arrowsOfRows(two, 5).every((a) => a.body === 5)).toBe(true);
    expect(arrowsOfRows(two, 5).length).toBe(3);
    expect(arrowsOfRows(two, 9).length).toBe(0);
  });

  it("shifts drag sideways, across the line of sight, and leaves weight where it acts", () => {
    const rows = restingRow();
    rows[8] = -0.02; // drag down, along the weight
    const arrows = arrowsOfRow(readForceRow(rows, 0));
    const drag = arrows.find((a) => a.kind === "drag")!;
    const view: [number, number, number] = [0, 0, -1];
    const tail = arrowTail(drag, view);
    expect(tail[1]).toBeCloseTo(drag.origin[1], 6);
    expect(tail[2]).toBeCloseTo(drag.origin[2], 6);
    expect(Math.abs(tail[0] - drag.origin[0])).toBeGreaterThan(0.02);
    const weight = arrows.find((a) => a.kind === "weight")!;
    expect(arrowTail(weight, view)).toEqual(weight.origin);
  });
});
