// Seeing the physics: the selected balloon (outlined, its card, its motion
// plotted), the force arrows with their legend, the teaching scenes' menu and
// the loaded scene's caption. Everything shown comes from the engine through
// the frames (sim/forcesFrame.ts); this class only routes it to its parts.

import type * as THREE from "three";
import { ForceArrows, arrowsOfRows, type Arrow } from "../render/forceArrows";
import { SelectionOutline } from "../render/selectionOutline";
import type { BalloonAssets } from "../render/balloons";
import type { SimBridge } from "../sim/bridge";
import type { WorldInfo } from "../sim/protocol";
import type { Scene } from "../scene/sceneSchema";
import { findForceRow, type Vec3 } from "../sim/forcesFrame";
import { BalloonCard, ForceLegend } from "../ui/balloonCard";
import { MotionPlot, WINDOW_S } from "../ui/motionPlot";
import { SceneCaption, aboutOfScene } from "../ui/caption";
import { LessonMenu, loadLessons, type Lesson } from "../ui/lessonMenu";
import type GUI from "lil-gui";

/** Turn of the view, radians, after which the arrows' sideways shifts are redone while no frame comes (paused). */
const VIEW_TURN = 0.05;

export class PhysicsView {
  readonly arrows = new ForceArrows();
  readonly outline = new SelectionOutline();
  readonly card: BalloonCard;
  readonly legend: ForceLegend;
  readonly plot: MotionPlot;
  readonly caption: SceneCaption;
  lessons: Lesson[] = [];
  menu: LessonMenu | null = null;
  /** Whether every balloon's forces are shown. */
  forcesOnAll = false;
  /** The teaching scene asked for, until its world is ready (then the address names it). */
  lessonPending: Lesson | null = null;
  private info: WorldInfo | null = null;
  private outlineReady = false;
  /** The frame whose forces the arrows show. */
  private arrowsFrame: unknown = null;
  private readonly view: Vec3 = [0, 0, -1];
  private readonly lastView: Vec3 = [0, 0, -1];
  private readonly viewVector: THREE.Vector3;

  constructor(
    scene: THREE.Scene,
    parent: HTMLElement,
    private readonly bridge: SimBridge,
    private readonly camera: THREE.Camera,
  ) {
    scene.add(this.arrows.group, this.outline.mesh);
    this.card = new BalloonCard(parent, () => this.select(-1), document.getElementById("hud"));
    // Stacked above the help line in the band between the left column and the panel (index.html).
    this.legend = new ForceLegend(document.getElementById("bottom-band") ?? parent);
    this.plot = new MotionPlot(parent);
    this.caption = new SceneCaption(parent);
    this.viewVector = camera.position.clone();
  }

  /** Selects body `index` of the current frame (-1: none): the worker follows it from then on. */
  select(index: number): void {
    this.bridge.select(index);
    this.plot.reset();
  }

  /** The selected body's dense index in the newest frame, -1 when none. */
  get selected(): number {
    return this.bridge.forces?.selected ?? -1;
  }

  setForcesOnAll(on: boolean): void {
    this.forcesOnAll = on;
    this.bridge.setForcesOnAll(on);
  }

  /** Fetches the teaching and example scenes and adds the panel's "Scenes" folder; `loaded` runs once one is chosen. */
  async addMenu(gui: GUI, assetsBase: string, loaded: (lesson: Lesson) => void): Promise<void> {
    this.lessons = await loadLessons(assetsBase);
    this.menu = new LessonMenu(gui, this.lessons, {
      load: (lesson) => {
        this.lessonPending = lesson;
        this.bridge.loadToml(lesson.toml);
        loaded(lesson);
      },
      forcesOnAll: (on) => this.setForcesOnAll(on),
    });
  }

  /**
   * A new world: the selection is gone (the worker dropped it), its caption
   * shows. Returns whether it is the teaching scene asked for.
   */
  worldReady(info: WorldInfo, scene: Scene): boolean {
    this.info = info;
    this.outlineReady = false;
    this.plot.reset();
    this.caption.show(aboutOfScene(scene));
    const lesson = this.lessonPending !== null;
    this.lessonPending = null;
    return lesson;
  }

  /** One animation frame: outline, arrows, card, legend and plot from the newest frame. */
  update(assets: BalloonAssets | null, alpha: number): void {
    const bridge = this.bridge;
    const f = bridge.current;
    const forces = bridge.forces;
    const info = this.info;
    if (info && assets && !this.outlineReady) {
      this.outline.setWorld({ latex: assets.geometry, latexDiameter: assets.diameter, diameters: info.diameters, foilMeshes: info.foilMeshes, trees: info.trees });
      this.outlineReady = true;
    }
    const selected = forces?.selected ?? -1;
    this.outline.update(selected, bridge.models[selected] ?? 0, bridge.prev, bridge.curr, alpha, bridge.scales[selected] ?? 1);
    this.camera.getWorldDirection(this.viewVector);
    this.view[0] = this.viewVector.x;
    this.view[1] = this.viewVector.y;
    this.view[2] = this.viewVector.z;
    const turned = Math.acos(Math.min(1, this.view[0] * this.lastView[0] + this.view[1] * this.lastView[1] + this.view[2] * this.lastView[2])) > VIEW_TURN;
    const newFrame = f !== this.arrowsFrame;
    const card = forces?.card ?? null;
    if (newFrame || turned) {
      this.arrowsFrame = f;
      this.lastView[0] = this.view[0];
      this.lastView[1] = this.view[1];
      this.lastView[2] = this.view[2];
      const arrows = forces ? arrowsOfRows(forces.rows, this.forcesOnAll ? -1 : selected) : [];
      this.arrows.set(arrows, this.view);
    }
    if (newFrame && card && f) {
      this.plot.window = WINDOW_S * Math.max(1, f.rate);
      // The terminal speed is a size; the balloon reaches it going up when it lifts, down when it sinks.
      const terminal = card.net_lift_n >= 0 ? card.terminal_speed_m_s : -card.terminal_speed_m_s;
      this.plot.push(f.simTime, card.height_m, card.vertical_speed_m_s, terminal);
    }
    this.card.show(card);
    this.plot.canvas.hidden = !card;
    // The motion plot takes the float plot's place while a balloon is selected (style.css).
    document.body.classList.toggle("balloon-selected", !!card);
    const row = forces && selected >= 0 ? findForceRow(forces.rows, selected) : null;
    this.legend.show(this.arrows.arrows.length > 0 || (this.forcesOnAll && !!forces) || !!card, row);
    this.plot.draw();
  }

  /** What the tests read: the selection, its card, the arrows drawn, the plot, the caption, the menu. */
  snapshot() {
    const forces = this.bridge.forces;
    const arrows: Arrow[] = this.arrows.arrows;
    return {
      selected: this.selected,
      card: forces?.card ?? null,
      arrows: arrows.map((a) => ({ kind: a.kind, body: a.body, origin: a.origin, force: a.force, length: a.length, clipped: a.clipped })),
      outlined: this.outline.mesh.visible,
      cardShown: !this.card.element.hidden,
      legendShown: !this.legend.element.hidden,
      plot: { points: this.plot.pointsShown(), terminal: this.plot.terminal, shown: !this.plot.canvas.hidden },
      caption: this.caption.visible ? this.caption.about : null,
      lessons: this.lessons.map((l) => ({ file: l.file, title: l.title })),
      forcesOnAll: this.forcesOnAll,
    };
  }
}
