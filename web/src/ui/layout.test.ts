import { describe, expect, it } from "vitest";
import { bottomTurn, layoutFor, PageLayout } from "./layout";

describe("the layout by window size", () => {
  it("is compact on phones and tablets, upright or on their side, and wide on laptops and desktops", () => {
    expect(layoutFor(360, 640)).toEqual({ compact: true, short: false, narrow: true });
    expect(layoutFor(390, 844)).toEqual({ compact: true, short: false, narrow: true });
    expect(layoutFor(844, 390)).toEqual({ compact: true, short: true, narrow: false });
    expect(layoutFor(768, 1024)).toEqual({ compact: true, short: false, narrow: false });
    expect(layoutFor(960, 600)).toEqual({ compact: false, short: false, narrow: false });
    expect(layoutFor(1280, 800)).toEqual({ compact: false, short: false, narrow: false });
    expect(layoutFor(1920, 1080)).toEqual({ compact: false, short: false, narrow: false });
  });

  it("is compact on a wide but short window (a laptop's browser with its toolbars)", () => {
    expect(layoutFor(1280, 500).compact).toBe(true);
    expect(layoutFor(1280, 500).short).toBe(false);
    expect(layoutFor(1280, 480).short).toBe(true);
  });
});

describe("whose turn the bottom-left corner is", () => {
  const phone = layoutFor(390, 844);
  const desktop = layoutFor(1280, 800);
  it("gives a selected balloon's motion plot the corner on any layout", () => {
    expect(bottomTurn(phone, false, true)).toBe("motion");
    expect(bottomTurn(desktop, false, true)).toBe("motion");
  });
  it("shows the help line on a phone until it has been read, then the float plot", () => {
    expect(bottomTurn(phone, false, false)).toBe("help");
    expect(bottomTurn(phone, true, false)).toBe("float");
  });
  it("shows the float plot beside the help line on a desktop", () => {
    expect(bottomTurn(desktop, false, false)).toBe("float");
  });
});

describe("PageLayout", () => {
  /** A stand-in for <body>: its classes and data attributes. */
  function fakeBody() {
    const classes = new Set<string>();
    return {
      classList: { toggle: (c: string, on: boolean) => (on ? classes.add(c) : classes.delete(c)) },
      dataset: {} as Record<string, string>,
      classes,
    };
  }

  it("keeps body's classes and data-bottom in step with the size, the help read and the selection", () => {
    const body = fakeBody();
    let size = { width: 390, height: 844 };
    const layout = new PageLayout(body as unknown as HTMLElement, () => size);
    expect([...body.classes].sort()).toEqual(["compact", "narrow"]);
    expect(body.dataset.bottom).toBe("help");
    layout.setSelected(true);
    expect(body.dataset.bottom).toBe("motion");
    layout.setSelected(false);
    layout.markHelpRead();
    expect(body.dataset.bottom).toBe("float");

    const heard: [boolean, boolean][] = [];
    layout.onChange((l, changed) => heard.push([l.compact, changed]));
    size = { width: 844, height: 390 };
    layout.resize();
    expect([...body.classes].sort()).toEqual(["compact", "short"]);
    size = { width: 1280, height: 800 };
    layout.resize();
    expect([...body.classes]).toEqual([]);
    expect(heard).toEqual([
      [true, false],
      [false, true],
    ]);
  });
});
