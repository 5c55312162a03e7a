import { describe, expect, it } from "vitest";
import { LONG_PRESS_MS, Press, longPressPops, pointerKind, ribbonEndReach, tapSlop } from "./gestures";

describe("pointer kinds", () => {
  it("reads PointerEvent.pointerType, anything unknown as a mouse", () => {
    expect(pointerKind("touch")).toBe("touch");
    expect(pointerKind("pen")).toBe("pen");
    expect(pointerKind("mouse")).toBe("mouse");
    expect(pointerKind("")).toBe("mouse");
  });
  it("gives a finger more slack and reach than a mouse, and the long press to fingers and pens", () => {
    expect(tapSlop("touch")).toBeGreaterThan(tapSlop("pen"));
    expect(tapSlop("pen")).toBeGreaterThan(tapSlop("mouse"));
    expect(ribbonEndReach("touch")).toBeGreaterThan(ribbonEndReach("mouse"));
    expect(longPressPops("touch")).toBe(true);
    expect(longPressPops("pen")).toBe(true);
    expect(longPressPops("mouse")).toBe(false);
  });
});

describe("a press", () => {
  it("is a tap when it stays within the slop, a drag once it leaves it (even if it comes back)", () => {
    const tap = new Press(100, 100, 0, "touch");
    tap.move(108, 104);
    expect(tap.isTap(106, 103)).toBe(true);

    const drag = new Press(100, 100, 0, "touch");
    drag.move(140, 100);
    expect(drag.dragged).toBe(true);
    expect(drag.isTap(100, 100)).toBe(false);

    // The same wobble is a drag for a mouse, whose click may move 5 px.
    expect(new Press(100, 100, 0, "mouse").isTap(108, 104)).toBe(false);
    expect(new Press(100, 100, 0, "mouse").isTap(103, 104)).toBe(true);
    expect(new Press(100, 100, 0, "mouse").isTap(106, 100)).toBe(false);
  });

  it("is a long press when a finger is held still long enough, once", () => {
    const p = new Press(50, 50, 1000, "touch");
    expect(p.longPressDue(1000 + LONG_PRESS_MS - 1)).toBe(false);
    p.move(53, 52);
    expect(p.longPressDue(1000 + LONG_PRESS_MS)).toBe(true);
    p.takeLongPress();
    expect(p.longPressed).toBe(true);
    expect(p.longPressDue(1000 + 2 * LONG_PRESS_MS)).toBe(false);
    // Its release neither selects nor throws.
    expect(p.isTap(50, 50)).toBe(false);
  });

  it("is no long press once it has moved, nor ever for a mouse", () => {
    const moved = new Press(50, 50, 0, "touch");
    moved.move(90, 50);
    expect(moved.longPressDue(10 * LONG_PRESS_MS)).toBe(false);
    expect(new Press(50, 50, 0, "mouse").longPressDue(10 * LONG_PRESS_MS)).toBe(false);
  });
});
