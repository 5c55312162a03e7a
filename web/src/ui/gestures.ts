// The gestures a finger or a pen makes on the room besides OrbitControls'
// (one finger orbits, two pinch and pan): a tap, a drag, and a long press,
// told apart by how far the pointer moved and how long it was held. Pure
// functions and a small state object over plain numbers, so the recogniser
// is unit-tested without a browser; controls.ts feeds it pointer events.

/** A press held this long (ms) without moving pops the balloon under a finger or a pen. */
export const LONG_PRESS_MS = 550;

/** What a pointer is, as PointerEvent.pointerType says ("" and unknown kinds read as a mouse). */
export type PointerKind = "mouse" | "touch" | "pen";

export function pointerKind(pointerType: string): PointerKind {
  return pointerType === "touch" || pointerType === "pen" ? pointerType : "mouse";
}

/**
 * How far (CSS px) a press may wander and still be a tap: a fingertip rolls
 * several pixels as it lifts, a mouse does not move by itself.
 */
export function tapSlop(kind: PointerKind): number {
  return kind === "touch" ? 12 : kind === "pen" ? 8 : 5;
}

/** How near (CSS px) a ribbon's free end is grabbed: a fingertip covers far more than a cursor's tip. */
export function ribbonEndReach(kind: PointerKind): number {
  return kind === "touch" ? 24 : kind === "pen" ? 12 : 8;
}

/** Whether a long press pops: for fingers and pens, which have no shift key; a mouse pops with shift- or alt-click. */
export function longPressPops(kind: PointerKind): boolean {
  return kind !== "mouse";
}

/** One press from down to up: where and when it began, and whether it has wandered past the tap slop. */
export class Press {
  private wandered = false;
  private popped = false;

  constructor(
    readonly x: number,
    readonly y: number,
    /** When it went down, ms. */
    readonly at: number,
    readonly kind: PointerKind,
  ) {}

  /** The pointer is at (x, y) now. */
  move(x: number, y: number): void {
    if (Math.hypot(x - this.x, y - this.y) > tapSlop(this.kind)) this.wandered = true;
  }

  /** Whether it has moved farther than a tap may: it is a drag from then on. */
  get dragged(): boolean {
    return this.wandered;
  }

  /** A long press is due at `now` (ms): held still long enough, by a finger or pen, not yet taken. */
  longPressDue(now: number): boolean {
    return longPressPops(this.kind) && !this.wandered && !this.popped && now - this.at >= LONG_PRESS_MS;
  }

  /** The long press was acted on: the release is neither a tap nor a throw. */
  takeLongPress(): void {
    this.popped = true;
  }

  get longPressed(): boolean {
    return this.popped;
  }

  /** Released at (x, y): a tap when it stayed within the slop and was not a long press. */
  isTap(x: number, y: number): boolean {
    this.move(x, y);
    return !this.wandered && !this.popped;
  }
}
