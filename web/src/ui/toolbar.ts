// The row of buttons under the room: add (placement mode, the CTRL key's
// twin, for hands without a keyboard), pause or play, single step, photo and
// record. Every key action a visitor needs has a button here, big enough for
// a fingertip; the panel keeps the rest. Each button carries data-action
// (the end-to-end tests' handle) and, for the toggles, aria-pressed.

export interface ToolbarActions {
  /** Placement mode on or off. */
  add(): void;
  togglePause(): void;
  step(): void;
  photo(): void;
  record(): void;
}

export type ToolbarAction = keyof ToolbarActions;

/** Each button: its action, its mark, its word, and the key that does the same (the tooltip says so). */
export const TOOLBAR_BUTTONS: { action: ToolbarAction; mark: string; label: string; key: string }[] = [
  { action: "add", mark: "+", label: "add", key: "CTRL" },
  { action: "togglePause", mark: "❚❚", label: "pause", key: "space" },
  { action: "step", mark: "▸|", label: "step", key: "N" },
  { action: "photo", mark: "◉", label: "photo", key: "P" },
  { action: "record", mark: "●", label: "record", key: "R" },
];

export class Toolbar {
  readonly element: HTMLElement;
  private readonly buttons = new Map<ToolbarAction, HTMLButtonElement>();
  private readonly state = { placement: false, paused: false, photo: false, recording: false };

  constructor(parent: HTMLElement, actions: ToolbarActions) {
    this.element = document.createElement("nav");
    this.element.id = "toolbar";
    this.element.setAttribute("aria-label", "simulation");
    for (const { action, mark, label, key } of TOOLBAR_BUTTONS) {
      const button = document.createElement("button");
      button.type = "button";
      button.dataset.action = action;
      button.title = `${label} (${key})`;
      button.innerHTML = `<span class="mark" aria-hidden="true"></span><span class="label"></span>`;
      button.querySelector(".mark")!.textContent = mark;
      button.querySelector(".label")!.textContent = label;
      // A button keeps no focus: space and the keys stay the page's, not a click on the last button tapped.
      button.addEventListener("pointerdown", (e) => e.preventDefault());
      button.addEventListener("click", () => actions[action]());
      this.buttons.set(action, button);
      this.element.appendChild(button);
    }
    this.buttons.get("add")!.setAttribute("aria-pressed", "false");
    this.buttons.get("togglePause")!.setAttribute("aria-pressed", "false");
    this.buttons.get("photo")!.setAttribute("aria-pressed", "false");
    this.buttons.get("record")!.setAttribute("aria-pressed", "false");
    parent.appendChild(this.element);
  }

  /** Placement mode is on: the add button is pressed, and pause and step wait (placement holds the simulation). */
  setPlacement(on: boolean): void {
    if (on === this.state.placement) return;
    this.state.placement = on;
    this.press("add", on, on ? "✓" : "+", on ? "done" : "add");
    this.buttons.get("togglePause")!.disabled = on;
    this.buttons.get("step")!.disabled = on;
  }

  /** Called every frame: touches the DOM only on a change. */
  setPaused(paused: boolean): void {
    if (paused === this.state.paused) return;
    this.state.paused = paused;
    this.press("togglePause", paused, paused ? "▶" : "❚❚", paused ? "play" : "pause");
  }

  setPhoto(on: boolean): void {
    if (on === this.state.photo) return;
    this.state.photo = on;
    this.press("photo", on, "◉", on ? "live" : "photo");
  }

  setRecording(on: boolean): void {
    if (on === this.state.recording) return;
    this.state.recording = on;
    this.press("record", on, on ? "■" : "●", on ? "stop" : "record");
  }

  private press(action: ToolbarAction, on: boolean, mark: string, label: string): void {
    const button = this.buttons.get(action)!;
    button.setAttribute("aria-pressed", String(on));
    button.querySelector(".mark")!.textContent = mark;
    button.querySelector(".label")!.textContent = label;
  }
}
