// The selected balloon's card (its mass, volume, gas, net lift, motion, as the
// engine states them) and the force arrows' legend (each kind's colour, the
// selected balloon's value of it, and the one length scale). DOM elements of
// their own, rewritten at most a few times a second.

import type { BodyCard } from "../sim/engine";
import { FORCE_KINDS, type ForceKind, type ForceRow } from "../sim/forcesFrame";
import { FORCE_STYLE, MAX_ARROW_M, NEWTONS_PER_METRE } from "../render/forceArrows";

/** Shortest time between two rewrites of the card, ms: readable numbers, no DOM work per frame. */
const REFRESH_MS = 150;

/** A signed number with its sign always written ("+0.081", "−0.020"). */
export function signed(value: number, digits: number): string {
  const text = Math.abs(value).toFixed(digits);
  if (Number(text) === 0) return text;
  return (value < 0 ? "−" : "+") + text;
}

/** The gas line: "helium, 0.48 mol", "air, 0.52 mol", or both amounts when mixed. */
export function gasText(card: Pick<BodyCard, "gas" | "helium_mol" | "air_mol">): string {
  if (card.gas === "helium") return `helium, ${card.helium_mol.toFixed(3)} mol`;
  if (card.gas === "air") return `air, ${card.air_mol.toFixed(3)} mol`;
  return `mixed: ${card.helium_mol.toFixed(3)} mol helium, ${card.air_mol.toFixed(3)} mol air`;
}

/** The card's lines, label and value, in the order shown. */
export function cardRows(card: BodyCard): [string, string][] {
  const lift = card.net_lift_n;
  const liftWord = lift > 0 ? "rises" : lift < 0 ? "sinks" : "floats";
  // Grams of lift need gravity: a room without it has none to weigh them by.
  const grams = Number.isFinite(card.net_lift_g) ? ` (${signed(card.net_lift_g, 1)} g)` : "";
  return [
    ["mass", `${(card.mass_kg * 1000).toFixed(2)} g`],
    ["volume", `${(card.volume_m3 * 1000).toFixed(2)} L`],
    ["gas", gasText(card)],
    ["net lift", `${signed(lift, 3)} N${grams}: ${liftWord}`],
    ["speed", `${card.speed_m_s.toFixed(2)} m/s (vertical ${signed(card.vertical_speed_m_s, 2)})`],
    ["terminal speed", `${card.terminal_speed_m_s.toFixed(2)} m/s`],
    ["air here", airText(card)],
    ["height, tilt", `${card.height_m.toFixed(2)} m, ${card.tilt_deg.toFixed(0)}°`],
  ];
}

/** The air line: the air's speed at the balloon and the balloon's speed through it (what its drag acts against), or "still". */
export function airText(card: Pick<BodyCard, "air_speed_m_s" | "speed_through_air_m_s">): string {
  if (card.air_speed_m_s < 0.005) return "still";
  return `${card.air_speed_m_s.toFixed(2)} m/s (the balloon through it ${card.speed_through_air_m_s.toFixed(2)} m/s)`;
}

/** A force's size in newtons: three significant places ("0.0532 N"), to a ten-thousandth below a thousandth. */
export function newtons(force: readonly number[]): string {
  const m = Math.hypot(force[0], force[1], force[2]);
  return `${m >= 0.001 ? m.toPrecision(3) : m.toFixed(4)} N`;
}

/** The legend's scale line: newtons per metre of arrow, and what a 10 cm arrow is. */
export function scaleText(newtonsPerMetre = NEWTONS_PER_METRE): string {
  return `arrow length: 1 m = ${newtonsPerMetre} N (10 cm = ${(newtonsPerMetre / 10).toPrecision(2)} N); longer than ${MAX_ARROW_M} m: cut`;
}

/** The selected balloon's card, top left under the HUD (`above`); its × deselects. */
export class BalloonCard {
  readonly element: HTMLElement;
  private readonly title: HTMLElement;
  private readonly body: HTMLElement;
  private lastWrite = -Infinity;
  private shownIndex = -2;

  constructor(
    parent: HTMLElement,
    close: () => void,
    private readonly above: HTMLElement | null = null,
  ) {
    this.element = document.createElement("section");
    this.element.id = "balloon-card";
    this.element.hidden = true;
    this.element.setAttribute("aria-live", "polite");
    const head = document.createElement("header");
    this.title = document.createElement("span");
    const button = document.createElement("button");
    button.type = "button";
    button.className = "close";
    button.textContent = "×";
    button.title = "Deselect (Esc)";
    button.addEventListener("click", close);
    head.append(this.title, button);
    this.body = document.createElement("table");
    this.element.append(head, this.body);
    parent.appendChild(this.element);
  }

  /** Shows `card` (null: hides the card); rewritten at most every `REFRESH_MS` unless the balloon changed. */
  show(card: BodyCard | null, now = performance.now()): void {
    if (!card) {
      this.element.hidden = true;
      this.shownIndex = -2;
      return;
    }
    if (card.index === this.shownIndex && now - this.lastWrite < REFRESH_MS) return;
    this.lastWrite = now;
    this.shownIndex = card.index;
    // The HUD grows a line when paused or in a mode: the card stays clear of it.
    if (this.above) this.element.style.top = `${Math.round(this.above.getBoundingClientRect().bottom) + 6}px`;
    this.title.textContent = `Balloon ${card.index + 1}`;
    this.body.replaceChildren(
      ...cardRows(card).map(([label, value]) => {
        const tr = document.createElement("tr");
        const th = document.createElement("th");
        th.textContent = label;
        const td = document.createElement("td");
        td.textContent = value;
        td.dataset.key = label;
        tr.append(th, td);
        return tr;
      }),
    );
    this.element.hidden = false;
  }
}

/** The arrows' legend: a swatch per kind, the selected balloon's values, the scale. */
export class ForceLegend {
  readonly element: HTMLElement;
  private readonly values = new Map<ForceKind, HTMLElement>();
  private lastWrite = -Infinity;

  constructor(parent: HTMLElement) {
    this.element = document.createElement("section");
    this.element.id = "force-legend";
    this.element.hidden = true;
    const list = document.createElement("ul");
    for (const kind of FORCE_KINDS) {
      const li = document.createElement("li");
      const swatch = document.createElement("span");
      swatch.className = "swatch";
      swatch.style.background = FORCE_STYLE[kind].color;
      const label = document.createElement("span");
      label.textContent = FORCE_STYLE[kind].label;
      const value = document.createElement("span");
      value.className = "value";
      this.values.set(kind, value);
      li.append(swatch, label, value);
      list.appendChild(li);
    }
    const scale = document.createElement("p");
    scale.textContent = scaleText();
    this.element.append(list, scale);
    parent.appendChild(this.element);
  }

  /** Shown while arrows are; `row`: the selected balloon's forces, written beside their kinds. */
  show(visible: boolean, row: ForceRow | null, now = performance.now()): void {
    this.element.hidden = !visible;
    if (!visible || now - this.lastWrite < REFRESH_MS) return;
    this.lastWrite = now;
    for (const kind of FORCE_KINDS) this.values.get(kind)!.textContent = row ? newtons(row.forces[kind]) : "";
  }
}
