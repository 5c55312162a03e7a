// Input mapping: which key or pointer gesture means what. Pure functions over
// plain event fields, so the mapping is unit-tested without a browser.

export type KeyAction =
  | { kind: "arrow"; direction: "left" | "right" | "up" | "down" }
  | { kind: "togglePlacement" }
  | { kind: "togglePause" }
  | { kind: "singleStep" }
  | { kind: "toggleDebug" }
  | { kind: "screenshot" }
  | { kind: "deselect" }
  | { kind: "photo" }
  | { kind: "record" }
  | { kind: "none" };

/** The fields of a KeyboardEvent the mapping reads. */
export interface KeyFields {
  key: string;
  repeat?: boolean;
  /** True when the key went down in a text field (the panel's number boxes). */
  inTextField?: boolean;
}

const ARROWS: Record<string, "left" | "right" | "up" | "down"> = {
  ArrowLeft: "left",
  ArrowRight: "right",
  ArrowUp: "up",
  ArrowDown: "down",
};

/** Maps a key press to an action. Arrow keys are held (see `arrowDirection`). */
export function mapKeyDown(e: KeyFields): KeyAction {
  const arrow = ARROWS[e.key];
  if (arrow) return e.inTextField ? { kind: "none" } : { kind: "arrow", direction: arrow };
  // CTRL toggles placement mode as in the original; a held key does not flicker it.
  if (e.key === "Control") return e.repeat ? { kind: "none" } : { kind: "togglePlacement" };
  if (e.inTextField || e.repeat) return { kind: "none" };
  switch (e.key) {
    case "Escape":
      return { kind: "deselect" };
    case " ":
      return { kind: "togglePause" };
    case "p":
    case "P":
      return { kind: "photo" };
    case "r":
    case "R":
      return { kind: "record" };
    case "n":
    case "N":
    case ".":
      return { kind: "singleStep" };
    case "d":
    case "D":
      return { kind: "toggleDebug" };
    case "s":
    case "S":
      return { kind: "screenshot" };
    default:
      return { kind: "none" };
  }
}

/** The arrow direction of a key, for key-up tracking; `null` for other keys. */
export function arrowDirection(key: string): "left" | "right" | "up" | "down" | null {
  return ARROWS[key] ?? null;
}

export type PointerAction = "place" | "grab" | "grabRibbon" | "pop" | "camera" | "none";

/** The fields of a pointer-down the mapping reads. */
export interface PointerFields {
  /** 0 left, 1 middle, 2 right. */
  button: number;
  shiftKey: boolean;
  altKey: boolean;
  /** Whether the pointer is over a balloon. */
  overBalloon: boolean;
  /** Whether the pointer is over a ribbon's free end (nearer than any balloon under it). */
  overRibbonEnd?: boolean;
  /** Whether placement mode (CTRL) is on. */
  placementMode: boolean;
}

/**
 * Maps a pointer-down to what it starts:
 * - placement mode: a left click places a balloon on the floor; nothing else;
 * - a left press on a ribbon's free end grabs the ribbon by it (its balloon follows);
 * - shift- or alt-click on a balloon pops it;
 * - left press on a balloon grabs it (drag, release to throw);
 * - anything else goes to the camera (OrbitControls: orbit, pan, zoom).
 */
export function mapPointerDown(e: PointerFields): PointerAction {
  if (e.placementMode) return e.button === 0 ? "place" : "none";
  if (e.button === 0 && e.overRibbonEnd && !e.shiftKey && !e.altKey) return "grabRibbon";
  if (e.button === 0 && e.overBalloon) return e.shiftKey || e.altKey ? "pop" : "grab";
  return "camera";
}

/**
 * What a left click (a press released without a drag) does to the
 * selection: on a balloon (its press grabbed it) it selects that balloon, on
 * empty space (its press went to the camera) it deselects; anything else
 * (popping, a ribbon's end, placement) leaves it.
 */
export function clickSelection(action: PointerAction, button: number): "select" | "deselect" | "none" {
  if (button !== 0) return "none";
  if (action === "grab") return "select";
  if (action === "camera") return "deselect";
  return "none";
}
