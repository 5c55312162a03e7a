// The page's layout by the size of its window: on a narrow or short window
// (a phone, a tablet, a small laptop window) the compact layout, where the
// panel folds behind its title, the HUD is one line and the help line and
// the float plot take turns in the bottom corner; else the three columns of
// style.css. The rules are pure functions of the size, so they are tested
// without a browser; `PageLayout` applies them as classes on <body>.

/** Narrower than this (CSS px), the layout is compact: the HUD, the middle band and the panel's 245 px do not fit side by side. */
export const COMPACT_WIDTH = 900;
/** Shorter than this, the layout is compact: the open panel and the HUD's stage timings would cover most of the room. */
export const COMPACT_HEIGHT = 560;
/** Shorter than this (a phone on its side), the selected balloon's card moves to the right-hand side, away from the plot. */
export const SHORT_HEIGHT = 500;
/** Narrower than this, the motion plot and the arrows' legend do not fit side by side above the toolbar: the legend is left out. */
export const NARROW_WIDTH = 520;

export interface Layout {
  /** The compact layout (body.compact). */
  compact: boolean;
  /** A phone on its side (body.short): only set with `compact`. */
  short: boolean;
  /** A phone upright (body.narrow): only set with `compact`. */
  narrow: boolean;
}

/** The layout of a window `width` × `height` CSS pixels. */
export function layoutFor(width: number, height: number): Layout {
  const compact = width < COMPACT_WIDTH || height < COMPACT_HEIGHT;
  return { compact, short: compact && height < SHORT_HEIGHT, narrow: compact && width < NARROW_WIDTH };
}

/** What the bottom-left corner shows: the help line, the float plot, or a selected balloon's motion plot. */
export type BottomTurn = "help" | "float" | "motion";

/**
 * Whose turn the bottom-left corner is. A selected balloon's motion plot
 * always; in the compact layout the help line until it has been read (the
 * first gesture on the room, or a tap on it), then the float plot. The wide
 * layout has room for the help line beside the plot: it shows the float plot.
 */
export function bottomTurn(layout: Layout, helpRead: boolean, selected: boolean): BottomTurn {
  if (selected) return "motion";
  if (layout.compact && !helpRead) return "help";
  return "float";
}

/**
 * The layout kept on <body>: the classes compact, short and narrow, and whose turn
 * the bottom-left corner is as data-bottom (style.css shows and hides by
 * them). Listeners hear each resize (the app folds the panel when the window
 * becomes compact).
 */
export class PageLayout {
  layout: Layout;
  private helpRead = false;
  private selected = false;
  private readonly listeners: ((layout: Layout, changed: boolean) => void)[] = [];

  constructor(
    private readonly body: HTMLElement,
    private readonly size: () => { width: number; height: number } = () => ({ width: window.innerWidth, height: window.innerHeight }),
  ) {
    const { width, height } = this.size();
    this.layout = layoutFor(width, height);
    this.apply();
  }

  /** Runs `listener` on every resize with the layout and whether its compactness changed. */
  onChange(listener: (layout: Layout, changed: boolean) => void): void {
    this.listeners.push(listener);
  }

  /** The window's new size: the classes follow. */
  resize(): void {
    const { width, height } = this.size();
    const next = layoutFor(width, height);
    const changed = next.compact !== this.layout.compact;
    this.layout = next;
    this.apply();
    for (const l of this.listeners) l(next, changed);
  }

  /** The help line has been read (a gesture on the room, a tap on it): in the compact layout the float plot takes its turn. */
  markHelpRead(): void {
    if (this.helpRead) return;
    this.helpRead = true;
    this.apply();
  }

  /** Whether a balloon is selected (its motion plot takes the corner); cheap when unchanged, so it can run every frame. */
  setSelected(selected: boolean): void {
    if (selected === this.selected) return;
    this.selected = selected;
    this.apply();
  }

  /** Whose turn the bottom-left corner is now. */
  get bottom(): BottomTurn {
    return bottomTurn(this.layout, this.helpRead, this.selected);
  }

  private apply(): void {
    const c = this.body.classList;
    c.toggle("compact", this.layout.compact);
    c.toggle("short", this.layout.short);
    c.toggle("narrow", this.layout.narrow);
    this.body.dataset.bottom = this.bottom;
  }
}
