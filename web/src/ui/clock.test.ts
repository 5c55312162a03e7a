import { describe, expect, it } from "vitest";
import { formatAchievedRate, formatCelsius, formatClock, formatRate } from "./clock";

describe("the simulated clock", () => {
  it("reads h:mm:ss since the start, rounded down", () => {
    expect(formatClock(0)).toBe("0:00:00");
    expect(formatClock(59.99)).toBe("0:00:59");
    expect(formatClock(61)).toBe("0:01:01");
    expect(formatClock(3600)).toBe("1:00:00");
    expect(formatClock(12 * 3600 + 34 * 60 + 5.5)).toBe("12:34:05");
    expect(formatClock(100 * 3600)).toBe("100:00:00");
  });

  it("reads 0:00:00 for what is not a time", () => {
    expect(formatClock(-3)).toBe("0:00:00");
    expect(formatClock(NaN)).toBe("0:00:00");
    expect(formatClock(Infinity)).toBe("0:00:00");
  });

  it("names the rates and rounds the achieved one to two figures", () => {
    expect(formatRate(1)).toBe("real time");
    expect(formatRate(60)).toBe("×60");
    expect(formatRate(3600)).toBe("×3\u2009600");
    expect(formatAchievedRate(3583.2)).toBe("×3\u2009600");
    expect(formatAchievedRate(1234)).toBe("×1\u2009200");
    expect(formatAchievedRate(57.4)).toBe("×57");
    expect(formatAchievedRate(0.93)).toBe("×1");
    expect(formatAchievedRate(0)).toBe("×0");
  });

  it("writes the temperature with one decimal", () => {
    expect(formatCelsius(20)).toBe("20.0 °C");
    expect(formatCelsius(-1.26)).toBe("-1.3 °C");
  });
});
