import { describe, expect, it } from "vitest";
import { arrowDirection, clickSelection, mapKeyDown, mapPointerDown } from "./input";

const pointer = { button: 0, shiftKey: false, altKey: false, overBalloon: false, placementMode: false };

describe("key mapping", () => {
  it("maps the arrow keys to the orbit directions", () => {
    expect(mapKeyDown({ key: "ArrowLeft" })).toEqual({ kind: "arrow", direction: "left" });
    expect(mapKeyDown({ key: "ArrowRight" })).toEqual({ kind: "arrow", direction: "right" });
    expect(mapKeyDown({ key: "ArrowUp" })).toEqual({ kind: "arrow", direction: "up" });
    expect(mapKeyDown({ key: "ArrowDown" })).toEqual({ kind: "arrow", direction: "down" });
    expect(arrowDirection("ArrowDown")).toBe("down");
    expect(arrowDirection("x")).toBeNull();
  });

  it("toggles placement on CTRL, once per press", () => {
    expect(mapKeyDown({ key: "Control" })).toEqual({ kind: "togglePlacement" });
    expect(mapKeyDown({ key: "Control", repeat: true })).toEqual({ kind: "none" });
    // CTRL works even while a panel field has focus: it is how the user leaves placement.
    expect(mapKeyDown({ key: "Control", inTextField: true })).toEqual({ kind: "togglePlacement" });
  });

  it("maps pause, single step, debug view and screenshot", () => {
    expect(mapKeyDown({ key: " " }).kind).toBe("togglePause");
    expect(mapKeyDown({ key: "p" }).kind).toBe("photo");
    expect(mapKeyDown({ key: "R" }).kind).toBe("record");
    expect(mapKeyDown({ key: "n" }).kind).toBe("singleStep");
    expect(mapKeyDown({ key: "d" }).kind).toBe("toggleDebug");
    expect(mapKeyDown({ key: "s" }).kind).toBe("screenshot");
    expect(mapKeyDown({ key: "q" }).kind).toBe("none");
  });

  it("ignores keys typed into the panel's text fields", () => {
    expect(mapKeyDown({ key: "ArrowLeft", inTextField: true }).kind).toBe("none");
    expect(mapKeyDown({ key: "n", inTextField: true }).kind).toBe("none");
    expect(mapKeyDown({ key: " ", inTextField: true }).kind).toBe("none");
  });

  it("ignores auto-repeat of toggles", () => {
    expect(mapKeyDown({ key: " ", repeat: true }).kind).toBe("none");
  });
});

describe("pointer mapping", () => {
  it("places on a left click in placement mode, whatever is under the pointer", () => {
    expect(mapPointerDown({ ...pointer, placementMode: true })).toBe("place");
    expect(mapPointerDown({ ...pointer, placementMode: true, overBalloon: true })).toBe("place");
    expect(mapPointerDown({ ...pointer, placementMode: true, button: 2 })).toBe("none");
  });

  it("grabs a balloon with a left press and pops it with shift or alt", () => {
    expect(mapPointerDown({ ...pointer, overBalloon: true })).toBe("grab");
    expect(mapPointerDown({ ...pointer, overBalloon: true, shiftKey: true })).toBe("pop");
    expect(mapPointerDown({ ...pointer, overBalloon: true, altKey: true })).toBe("pop");
  });

  it("grabs a ribbon by its free end with a left press, and pops its balloon with shift", () => {
    expect(mapPointerDown({ ...pointer, overRibbonEnd: true })).toBe("grabRibbon");
    expect(mapPointerDown({ ...pointer, overRibbonEnd: true, overBalloon: true })).toBe("grabRibbon");
    expect(mapPointerDown({ ...pointer, overRibbonEnd: true, overBalloon: true, shiftKey: true })).toBe("pop");
    expect(mapPointerDown({ ...pointer, overRibbonEnd: true, button: 2 })).toBe("camera");
    expect(mapPointerDown({ ...pointer, overRibbonEnd: true, placementMode: true })).toBe("place");
  });

  it("leaves everything else to the camera controls", () => {
    expect(mapPointerDown(pointer)).toBe("camera");
    expect(mapPointerDown({ ...pointer, overBalloon: true, button: 2 })).toBe("camera");
    expect(mapPointerDown({ ...pointer, shiftKey: true })).toBe("camera");
  });
});

describe("selection by click", () => {
  it("selects on a click on a balloon, deselects on a click on empty space, with the left button only", () => {
    expect(clickSelection(mapPointerDown({ ...pointer, overBalloon: true }), 0)).toBe("select");
    expect(clickSelection(mapPointerDown(pointer), 0)).toBe("deselect");
    expect(clickSelection(mapPointerDown({ ...pointer, button: 2 }), 2)).toBe("none");
  });

  it("leaves the selection on popping, on a ribbon's end and in placement mode", () => {
    expect(clickSelection(mapPointerDown({ ...pointer, overBalloon: true, shiftKey: true }), 0)).toBe("none");
    expect(clickSelection(mapPointerDown({ ...pointer, overBalloon: true, overRibbonEnd: true }), 0)).toBe("none");
    expect(clickSelection(mapPointerDown({ ...pointer, overBalloon: true, placementMode: true }), 0)).toBe("none");
  });

  it("deselects on Esc, but not from a text field", () => {
    expect(mapKeyDown({ key: "Escape" })).toEqual({ kind: "deselect" });
    expect(mapKeyDown({ key: "Escape", inTextField: true })).toEqual({ kind: "none" });
  });
});
