// A finger on the page, for the touch specs: Chromium's own touch input
// (CDP Input.dispatchTouchEvent), which the page receives as pointer events
// of type "touch", as from a phone's screen. Playwright's touchscreen only taps.
// Each event carries the time the gesture means it to have (a tap 60 ms
// long), not the time it was sent: Chromium answers each event only once
// the page has taken it, which on a loaded machine drawing through
// SwiftShader is a second or more, and a tap would read as a long press.

import type { CDPSession, Page } from "@playwright/test";

export interface Point {
  x: number;
  y: number;
}

/** A finger on `page`: down, along a path, held, up. */
export class Finger {
  /** The gesture's clock, s since the epoch, as CDP's `timestamp` reads it. */
  private at = 0;

  private constructor(
    private readonly cdp: CDPSession,
    private readonly page: Page,
  ) {}

  static async on(page: Page): Promise<Finger> {
    return new Finger(await page.context().newCDPSession(page), page);
  }

  /** One touch event, `afterMs` after the gesture's previous one (a touchStart begins the gesture's clock now). */
  private async touch(type: "touchStart" | "touchMove" | "touchEnd", points: Point[], afterMs = 0): Promise<void> {
    this.at = type === "touchStart" ? Date.now() / 1000 : this.at + afterMs / 1000;
    if (afterMs > 0) await this.page.waitForTimeout(afterMs);
    await this.cdp.send("Input.dispatchTouchEvent", { type, touchPoints: points.map((p, id) => ({ x: p.x, y: p.y, id })), timestamp: this.at });
  }

  /** Touches at `from`, moves along `path` (`stepMs` apart) and lifts at its end. */
  async drag(from: Point, path: Point[], stepMs = 50): Promise<void> {
    await this.touch("touchStart", [from]);
    for (const p of path) await this.touch("touchMove", [p], stepMs);
    await this.touch("touchEnd", [], stepMs);
  }

  /** Touches at `at`, holds still for `ms`, lifts. */
  async hold(at: Point, ms: number): Promise<void> {
    await this.touch("touchStart", [at]);
    await this.touch("touchEnd", [], ms);
  }

  /** A quick tap at `at`. */
  async tap(at: Point): Promise<void> {
    await this.hold(at, 60);
  }
}

/** Points `n` steps from `from` by `(dx, dy)` in all. */
export function line(from: Point, dx: number, dy: number, n = 10): Point[] {
  return Array.from({ length: n }, (_, i) => ({ x: from.x + (dx * (i + 1)) / n, y: from.y + (dy * (i + 1)) / n }));
}

/**
 * A balloon whose centre shows on the canvas itself (no overlay above it),
 * nearest the view's middle: its index and where it is on the screen.
 */
export function reachableBalloon(page: Page): Promise<{ index: number; x: number; y: number } | null> {
  return page.evaluate(() => {
    const up = window.__up!;
    const canvas = document.getElementById("view");
    let best: { index: number; x: number; y: number; d: number } | null = null;
    for (let i = 0; i < up.balloonCount(); i++) {
      const c = up.balloonCenter(i);
      if (!c) continue;
      const p = up.project(c[0], c[1], c[2]);
      if (document.elementFromPoint(p.x, p.y) !== canvas) continue;
      const d = Math.hypot(p.x - innerWidth / 2, p.y - innerHeight / 2);
      if (!best || d < best.d) best = { index: i, x: p.x, y: p.y, d };
    }
    return best && { index: best.index, x: best.x, y: best.y };
  });
}
