// What the stage draws of the simulated world: the room, the balloons (once
// their model has loaded), their ribbons and the debug view, updated from the
// physics worker's newest frame every animation frame.

import * as THREE from "three";
import { buildRoom } from "./room";
import { buildFurniture } from "./furniture";
import { Balloons, loadBalloonAssets, type BalloonAssets } from "./balloons";
import { DebugView } from "./debugView";
import { Ribbons } from "./ribbons";
import { RIBBON_POINT_STRIDE } from "../sim/frameLayout";
import type { SimBridge } from "../sim/bridge";
import type { WorldInfo } from "../sim/protocol";

export class WorldView {
  readonly debug = new DebugView();
  balloons: Balloons | null = null;
  /** Made with the first world (its ribbon width comes from the engine). */
  ribbons: Ribbons | null = null;
  assets: BalloonAssets | null = null;
  private room: THREE.Group | null = null;
  private roomKey = "";
  private furniture: THREE.Mesh | null = null;
  private furnitureKey = "";
  private info: WorldInfo | null = null;
  /** Frame version whose colours and models the balloons show (-1: none yet). */
  private drawnVersion = -1;
  /** Frame version whose ribbon tables the ribbons show (-1: none yet). */
  private ribbonVersion = -1;
  /** The frame whose contacts the debug view shows. */
  private contactsFrame: unknown = null;

  constructor(private readonly scene: THREE.Scene) {
    scene.add(this.debug.group);
  }

  /** Loads the balloon model; the balloons are drawn from then on. */
  async loadAssets(baseUrl: string): Promise<void> {
    const assets = await loadBalloonAssets(baseUrl);
    this.assets = assets;
    this.balloons = new Balloons(assets);
    this.scene.add(this.balloons.group);
    if (this.info) this.balloons.setWorld(this.info.palette, this.info.colorNames, this.info.diameters, this.info.foilMeshes, this.info.finishes);
  }

  /** A new world from the engine; returns whether its room differs from the one drawn. */
  setWorld(info: WorldInfo): boolean {
    this.info = info;
    const roomKey = info.room.vertices.join(",");
    const roomChanged = roomKey !== this.roomKey;
    if (roomChanged) {
      if (this.room) this.scene.remove(this.room);
      this.room = buildRoom(info.room);
      this.scene.add(this.room);
      this.roomKey = roomKey;
    }
    const furnitureKey = info.furniture.vertices.join(",");
    if (furnitureKey !== this.furnitureKey) {
      if (this.furniture) {
        this.scene.remove(this.furniture);
        this.furniture.geometry.dispose();
      }
      this.furniture = buildFurniture(info.furniture);
      if (this.furniture) this.scene.add(this.furniture);
      this.furnitureKey = furnitureKey;
    }
    this.debug.setTrees(info.trees);
    if (!this.ribbons) {
      this.ribbons = new Ribbons(info.constants.ribbon_width_m, info.constants.weight_radius_m);
      this.scene.add(this.ribbons.group);
    }
    this.ribbonVersion = -1;
    this.balloons?.setWorld(info.palette, info.colorNames, info.diameters, info.foilMeshes, info.finishes);
    this.drawnVersion = -1;
    return roomChanged;
  }

  /** Debug view on or off; `contacts` are the bridge's current ones (cleared when off). */
  setDebug(on: boolean, contacts: Float32Array): void {
    this.debug.visible = on;
    this.contactsFrame = null;
    if (!on) this.debug.setContacts(contacts, 0);
  }

  /** Takes the newest frame's dents as it arrives (frames may come faster than the page draws). */
  takeFrame(bridge: SimBridge): void {
    const f = bridge.current;
    if (f && this.balloons && f.version === this.drawnVersion) this.balloons.takeDents(bridge.squash, f.stepTime);
  }

  /** Poses of the newest frame, interpolated to `nowAbs` (ms since the epoch); false until balloons can be drawn. */
  update(bridge: SimBridge, nowAbs: number): boolean {
    const f = bridge.current;
    const balloons = this.balloons;
    if (!f || !balloons) return false;
    if (f.version !== this.drawnVersion && bridge.colors.length === f.count) {
      balloons.setBodies(bridge.colors, bridge.models);
      this.drawnVersion = f.version;
    }
    balloons.update(bridge.prev, bridge.curr, f.count, bridge.alpha(nowAbs), bridge.scales, nowAbs);
    const ribbons = this.ribbons;
    const tables = bridge.ribbons;
    if (ribbons && f.version !== this.ribbonVersion && (tables.offsets[tables.bodies.length] ?? 0) * RIBBON_POINT_STRIDE === f.ribbonFloats) {
      ribbons.setRibbons(tables, bridge.ribbonsCurr);
      this.ribbonVersion = f.version;
    }
    if (ribbons && this.ribbonVersion === f.version) ribbons.update(bridge.ribbonsPrev, bridge.ribbonsCurr, bridge.alpha(nowAbs));
    if (this.debug.visible) {
      this.debug.update(bridge.curr, 0, f.count, bridge.models, bridge.scales);
      this.debug.setRibbonPoints(bridge.ribbonsCurr);
      if (this.contactsFrame !== f) {
        this.debug.setContacts(bridge.contacts, f.contactCount);
        this.contactsFrame = f;
      }
    }
    return true;
  }
}
