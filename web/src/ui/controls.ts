// Camera and pointer controls: arrow-key orbit at constant distance around the
// centre of the room, OrbitControls for the mouse, CTRL placement mode (the
// camera below the room looking up, a click adds a balloon on the floor),
// grab / drag / throw / pop of balloons, and grab / drag of a ribbon by its
// free end. Pointer events throughout, so a finger or a pen does what the
// mouse does (gestures.ts tells a tap from a drag and a long press, which
// pops; OrbitControls' touch: one finger orbits, two pinch and pan).

import * as THREE from "three";
import { OrbitControls } from "three/examples/jsm/controls/OrbitControls.js";
import { anyArrowHeld, orbitAngles, orbitPosition, portraitPullBack, stepOrbit, type ArrowState } from "./orbit";
import { arrowDirection, clickSelection, mapKeyDown, mapPointerDown, type KeyAction } from "./input";
import { LONG_PRESS_MS, Press, longPressPops, pointerKind, ribbonEndReach, type PointerKind } from "./gestures";
import { pickBalloon, pickRibbonEnd, rayHorizontalPlane, type BodySphere, type Ray } from "../sim/pick";
import type { SimBridge } from "../sim/bridge";
import type { TreeNode } from "../sim/engine";

export interface ControlEvents {
  /** A key action other than the arrows and CTRL (pause, step, debug, screenshot). */
  action(action: KeyAction): void;
  /** Placement mode was entered or left. */
  placement(on: boolean): void;
  /** A click selected body `index` of the current frame, or empty space (-1). */
  select(index: number): void;
  /** A pointer went down on the room: the visitor has found the gestures (the compact layout's help line gives way). */
  touched(): void;
}

/** How near the mouse, in CSS pixels, a ribbon's free end is grabbed (a finger reaches farther: gestures.ts). */
export const RIBBON_END_PIXELS = ribbonEndReach("mouse");

interface RoomBox {
  halfWidth: number;
  halfDepth: number;
  top: number;
}

export class Controls {
  readonly orbit: OrbitControls;
  readonly keys: ArrowState = { left: false, right: false, up: false, down: false };
  placement = false;
  private room: RoomBox = { halfWidth: 3, halfDepth: 3, top: 4.5 };
  private roots: BodySphere[] = [];
  private leaves: BodySphere[][] = [];
  private saved: { position: THREE.Vector3; target: THREE.Vector3; paused: boolean } | null = null;
  private grabbing = false;
  private readonly dragPlane = new THREE.Plane();
  private readonly raycaster = new THREE.Raycaster();
  private readonly ndc = new THREE.Vector2();
  private readonly hitPoint = new THREE.Vector3();
  /** The press under way on the room (the primary pointer's), and what a tap on it selects. */
  private down: { press: Press; select: number | null; pop: number | null } | null = null;
  /** Pointers down on the room now: a second one makes the gesture OrbitControls' pinch and pan. */
  private readonly pointers = new Set<number>();
  private longPressTimer: ReturnType<typeof setTimeout> | null = null;

  constructor(
    private readonly camera: THREE.PerspectiveCamera,
    private readonly canvas: HTMLCanvasElement,
    private readonly bridge: SimBridge,
    private readonly events: ControlEvents,
  ) {
    // Our pointer-down runs before OrbitControls' (registered first) and turns
    // it off while a balloon is held or placement mode is on.
    canvas.addEventListener("pointerdown", (e) => this.pointerDown(e));
    this.orbit = new OrbitControls(camera, canvas);
    this.orbit.enableDamping = true;
    this.orbit.dampingFactor = 0.12;
    this.orbit.maxDistance = 200;
    this.orbit.minDistance = 0.5;
    canvas.addEventListener("pointermove", (e) => this.pointerMove(e));
    canvas.addEventListener("pointerup", (e) => this.pointerUp(e));
    canvas.addEventListener("pointercancel", (e) => this.pointerUp(e));
    canvas.addEventListener("contextmenu", (e) => e.preventDefault());
    window.addEventListener("keydown", (e) => this.keyDown(e));
    window.addEventListener("keyup", (e) => this.keyUp(e));
    window.addEventListener("blur", () => Object.assign(this.keys, { left: false, right: false, up: false, down: false }));
  }

  /** The centre of the room, which the arrow keys orbit. */
  center(): THREE.Vector3 {
    return new THREE.Vector3(0, this.room.top * 0.55, 0);
  }

  /** A new world: its room and the balloon models' sphere trees (for picking). */
  setWorld(room: RoomBox, trees: TreeNode[][], resetView: boolean): void {
    this.room = room;
    this.roots = trees.map((t) => ({ center: t[0].center, radius: t[0].radius }));
    this.leaves = trees.map((t) => t.filter((n) => n.leaf).map((n) => ({ center: n.center, radius: n.radius })));
    if (resetView) this.homeView();
  }

  /** The default view: outside the room, a little above, looking at its centre. */
  homeView(): void {
    const size = Math.max(this.room.halfWidth * 2, this.room.halfDepth * 2, this.room.top);
    // A window taller than wide (a phone upright) sees less across: step back until the room's width fits.
    const distance = (size * 1.3 + 1) * portraitPullBack(this.camera.aspect);
    // Just below the top of the walls: the ceiling, where the balloons gather, shows from inside.
    const p = orbitPosition(this.center(), { azimuth: 0.6, elevation: 0.03, distance });
    this.camera.up.set(0, 1, 0);
    this.camera.position.set(p.x, p.y, p.z);
    this.orbit.target.copy(this.center());
    this.camera.lookAt(this.orbit.target);
    this.orbit.update();
  }

  /** Per animation frame: arrow-key orbit and OrbitControls damping. */
  update(dt: number): void {
    if (!this.placement && anyArrowHeld(this.keys)) {
      const center = this.center();
      const angles = stepOrbit(orbitAngles(center, this.camera.position), this.keys, dt);
      const p = orbitPosition(center, angles);
      this.camera.position.set(p.x, p.y, p.z);
      this.orbit.target.copy(center);
      this.camera.lookAt(center);
    }
    if (!this.placement) this.orbit.update();
  }

  private inTextField(e: KeyboardEvent): boolean {
    const t = e.target as HTMLElement | null;
    return !!t && (t.tagName === "INPUT" || t.tagName === "TEXTAREA" || t.tagName === "SELECT" || t.isContentEditable);
  }

  private keyDown(e: KeyboardEvent): void {
    const action = mapKeyDown({ key: e.key, repeat: e.repeat, inTextField: this.inTextField(e) });
    switch (action.kind) {
      case "arrow":
        this.keys[action.direction] = true;
        e.preventDefault();
        return;
      case "togglePlacement":
        this.setPlacement(!this.placement);
        return;
      case "none":
        return;
      default:
        e.preventDefault();
        this.events.action(action);
    }
  }

  private keyUp(e: KeyboardEvent): void {
    const direction = arrowDirection(e.key);
    if (direction) this.keys[direction] = false;
  }

  /** CTRL: pause and look up from below the floor; CTRL again: back to the previous view and state. */
  setPlacement(on: boolean): void {
    if (on === this.placement) return;
    this.placement = on;
    if (on) {
      this.release();
      this.saved = { position: this.camera.position.clone(), target: this.orbit.target.clone(), paused: this.bridge.paused };
      this.bridge.setPaused(true);
      this.orbit.enabled = false;
      // Far enough below that the whole floor fits the view.
      const half = Math.max(this.room.halfWidth, this.room.halfDepth / Math.max(0.3, this.camera.aspect));
      const below = (half * 1.15) / Math.tan(THREE.MathUtils.degToRad(this.camera.fov / 2));
      this.camera.up.set(0, 0, -1);
      this.camera.position.set(0, -below, 0);
      this.camera.lookAt(0, this.room.top, 0);
    } else {
      const saved = this.saved;
      this.camera.up.set(0, 1, 0);
      if (saved) {
        this.camera.position.copy(saved.position);
        this.orbit.target.copy(saved.target);
        this.camera.lookAt(saved.target);
        this.bridge.setPaused(saved.paused);
      }
      this.orbit.enabled = true;
      this.orbit.update();
    }
    this.events.placement(on);
  }

  /** The pointer's world ray. */
  ray(clientX: number, clientY: number): Ray {
    const rect = this.canvas.getBoundingClientRect();
    this.ndc.set(((clientX - rect.left) / rect.width) * 2 - 1, -((clientY - rect.top) / rect.height) * 2 + 1);
    this.raycaster.setFromCamera(this.ndc, this.camera);
    const { origin, direction } = this.raycaster.ray;
    return { origin: [origin.x, origin.y, origin.z], direction: [direction.x, direction.y, direction.z] };
  }

  /** The floor point under the pointer, inside the room with a margin, or null. */
  floorPoint(clientX: number, clientY: number, margin = 0.15): [number, number, number] | null {
    const p = rayHorizontalPlane(this.ray(clientX, clientY), 0);
    if (!p) return null;
    const inside = Math.abs(p[0]) <= this.room.halfWidth - margin && Math.abs(p[2]) <= this.room.halfDepth - margin;
    return inside ? p : null;
  }

  private pick(clientX: number, clientY: number) {
    const b = this.bridge;
    if (!b.current) return null;
    return pickBalloon(this.ray(clientX, clientY), b.curr, b.current.count, this.roots, this.leaves, b.models, b.scales);
  }

  /** The ribbon free end within reach of the pointer (`ribbonEndReach`), if any. */
  private pickRibbonEnd(clientX: number, clientY: number, kind: PointerKind) {
    const b = this.bridge;
    if (!b.current || b.ribbons.bodies.length === 0) return null;
    const height = this.canvas.getBoundingClientRect().height || 1;
    const radiansPerPixel = (2 * Math.tan(THREE.MathUtils.degToRad(this.camera.fov / 2))) / height;
    return pickRibbonEnd(this.ray(clientX, clientY), b.ribbonsCurr, b.ribbons.offsets, radiansPerPixel, ribbonEndReach(kind));
  }

  /** Starts dragging on the plane facing the camera through `point`. */
  private startDrag(e: PointerEvent, point: [number, number, number]): void {
    this.orbit.enabled = false;
    this.grabbing = true;
    this.canvas.setPointerCapture(e.pointerId);
    this.hitPoint.set(...point);
    const normal = this.camera.getWorldDirection(new THREE.Vector3());
    this.dragPlane.setFromNormalAndCoplanarPoint(normal, this.hitPoint);
  }

  private pointerDown(e: PointerEvent): void {
    this.events.touched();
    // A primary pointer is the first of its kind down: any left from before lost their up event.
    if (e.isPrimary) this.pointers.clear();
    this.pointers.add(e.pointerId);
    if (this.pointers.size > 1) {
      // A second finger: pinch and pan. Whatever the first one began (a grab, a tap, a long press) is dropped.
      this.cancelPress();
      this.release();
      if (!this.placement) this.orbit.enabled = true;
      return;
    }
    const kind = pointerKind(e.pointerType);
    const picking = !this.placement && e.button === 0;
    const hit = picking ? this.pick(e.clientX, e.clientY) : null;
    const end = picking ? this.pickRibbonEnd(e.clientX, e.clientY, kind) : null;
    // A free end hidden behind a balloon is not grabbed through it.
    const overRibbonEnd = !!end && (!hit || end.distance <= hit.distance);
    const action = mapPointerDown({ button: e.button, shiftKey: e.shiftKey, altKey: e.altKey, overBalloon: !!hit, overRibbonEnd, placementMode: this.placement });
    const selection = clickSelection(action, e.button);
    this.down = {
      // The event's own time (performance.now()'s clock): a busy page may run this handler late.
      press: new Press(e.clientX, e.clientY, e.timeStamp, kind),
      select: selection === "select" && hit ? hit.index : selection === "deselect" ? -1 : null,
      pop: action === "grab" && hit ? hit.index : null,
    };
    if (action === "grabRibbon" && end) {
      this.startDrag(e, end.position);
      this.bridge.grabRibbon(end.ribbon, end.point, end.position);
    } else if (action === "grab" && hit) {
      this.startDrag(e, hit.point);
      this.bridge.grab(hit.index, hit.point);
      // A finger or a pen held still on a balloon pops it (the mouse's shift-click).
      if (longPressPops(kind)) this.longPressTimer = setTimeout(() => this.longPress(), LONG_PRESS_MS);
    } else if (action === "pop" && hit) {
      this.orbit.enabled = false;
      this.bridge.pop(hit.index);
    } else if (action === "place" || action === "none") {
      this.orbit.enabled = false;
    } else if (!this.placement) {
      this.orbit.enabled = true;
    }
  }

  /**
   * The long-press timer ran out: pop the balloon held, if the press is still
   * a long press at the next animation frame. The browser hands over pointer
   * moves just before a frame, so on a page drawing few frames a second the
   * moves of a drag already under way arrive by then, and the drag is not
   * taken for a long press.
   */
  private longPress(): void {
    this.longPressTimer = null;
    const down = this.down;
    requestAnimationFrame(() => {
      if (this.down === down) this.popIfLongPress(performance.now());
    });
  }

  /** Pops the balloon under the press if it has been held still long enough by `now` (ms). */
  private popIfLongPress(now: number): void {
    const down = this.down;
    if (!down || down.pop === null || !down.press.longPressDue(now)) return;
    down.press.takeLongPress();
    this.release();
    this.bridge.pop(down.pop);
  }

  private cancelPress(): void {
    if (this.longPressTimer !== null) clearTimeout(this.longPressTimer);
    this.longPressTimer = null;
    this.down = null;
  }

  private pointerMove(e: PointerEvent): void {
    if (this.down && this.pointers.size === 1) this.down.press.move(e.clientX, e.clientY);
    if (!this.grabbing) return;
    const r = this.ray(e.clientX, e.clientY);
    const ray = new THREE.Ray(new THREE.Vector3(...r.origin), new THREE.Vector3(...r.direction));
    const target = ray.intersectPlane(this.dragPlane, new THREE.Vector3());
    if (target) this.bridge.dragTo([target.x, target.y, target.z]);
  }

  private pointerUp(e: PointerEvent): void {
    const wasDown = this.pointers.delete(e.pointerId);
    const down = this.down;
    // Lifting one of two fingers ends the pinch; the press, if any, was dropped when the second came.
    if (!wasDown || this.pointers.size > 0) return;
    // A page busy drawing may hand over the finger's lift before the overdue timer: the press's length decides.
    if (e.type === "pointerup") this.popIfLongPress(e.timeStamp);
    this.cancelPress();
    const tap = !!down && e.type === "pointerup" && e.button === 0 && down.press.isTap(e.clientX, e.clientY);
    if (this.placement && tap) {
      const p = this.floorPoint(e.clientX, e.clientY);
      if (p) this.bridge.addOnFloor(p[0], p[2]);
    }
    if (tap && down.select !== null) this.events.select(down.select);
    this.release();
    if (!this.placement) this.orbit.enabled = true;
  }

  private release(): void {
    if (this.grabbing) {
      this.grabbing = false;
      this.bridge.release();
    }
  }
}
