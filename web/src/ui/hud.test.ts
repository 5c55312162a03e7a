import { describe, expect, it } from "vitest";
import { clockText, compactLine } from "./hud";

describe("the HUD's clock line", () => {
  it("shows the time since the start, the room's temperature and the pace", () => {
    expect(clockText({ simTime: 3723, airTemperatureC: 20, rate: 1, achievedRate: 1 })).toBe("Clock 1:02:03 · 20.0 °C · real time");
    expect(clockText({ simTime: 5 * 3600, airTemperatureC: 12.34, rate: 3600, achievedRate: 2873 })).toBe(
      "Clock 5:00:00 · 12.3 °C · ×3\u2009600 (now ×2\u2009900)",
    );
  });
});

describe("the compact HUD's line", () => {
  it("says the count, the clock, the pace in a time-lapse, the frame rate and whether the page draws for less", () => {
    expect(compactLine({ count: 50, simTime: 83, rate: 1, fps: 58.6, lighter: false })).toBe("50 balloons · 0:01:23 · 59 fps ▾");
    expect(compactLine({ count: 1, simTime: 3600, rate: 60, fps: NaN, lighter: true })).toBe("1 balloon · 1:00:00 · ×60 · – fps · lighter ▾");
  });
});
