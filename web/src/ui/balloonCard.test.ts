import { describe, expect, it } from "vitest";
import { airText, cardRows, gasText, newtons, scaleText, signed } from "./balloonCard";
import type { BodyCard } from "../sim/engine";

const card: BodyCard = {
  index: 3,
  mass_kg: 0.00562,
  volume_m3: 0.01153,
  helium_mol: 0.4791,
  air_mol: 0,
  helium_fraction: 1,
  net_lift_n: 0.0807,
  net_lift_g: 8.23,
  speed_m_s: 0.612,
  vertical_speed_m_s: 0.598,
  height_m: 1.234,
  tilt_deg: 12.4,
  terminal_speed_m_s: 0.741,
  gas: "helium",
  air_velocity_m_s: [0, 0, 0],
  air_speed_m_s: 0,
  speed_through_air_m_s: 0.612,
};

describe("the balloon card", () => {
  it("writes each value in its unit, in grams, litres, newtons, m/s, metres and degrees", () => {
    const rows = Object.fromEntries(cardRows(card));
    expect(rows.mass).toBe("5.62 g");
    expect(rows.volume).toBe("11.53 L");
    expect(rows.gas).toBe("helium, 0.479 mol");
    expect(rows["net lift"]).toBe("+0.081 N (+8.2 g): rises");
    expect(rows.speed).toBe("0.61 m/s (vertical +0.60)");
    expect(rows["terminal speed"]).toBe("0.74 m/s");
    expect(rows["height, tilt"]).toBe("1.23 m, 12°");
    expect(rows["air here"]).toBe("still");
  });

  it("gives the air's speed at the balloon and the balloon's speed through it", () => {
    const windy = { ...card, air_velocity_m_s: [1.2, 0, 0.5] as [number, number, number], air_speed_m_s: 1.3, speed_through_air_m_s: 0.84 };
    expect(Object.fromEntries(cardRows(windy))["air here"]).toBe("1.30 m/s (the balloon through it 0.84 m/s)");
    expect(airText({ air_speed_m_s: 0.004, speed_through_air_m_s: 0.2 })).toBe("still");
  });

  it("says a heavier-than-air balloon sinks, and names both gases when mixed", () => {
    const air = { ...card, gas: "air" as const, helium_mol: 0, air_mol: 0.5, net_lift_n: -0.052, net_lift_g: -5.3, vertical_speed_m_s: -0.4 };
    const rows = Object.fromEntries(cardRows(air));
    expect(rows.gas).toBe("air, 0.500 mol");
    expect(rows["net lift"]).toBe("−0.052 N (−5.3 g): sinks");
    expect(gasText({ gas: "mixed", helium_mol: 0.3, air_mol: 0.1 })).toBe("mixed: 0.300 mol helium, 0.100 mol air");
  });

  it("leaves the grams out where there is no gravity to weigh the lift by", () => {
    const rows = Object.fromEntries(cardRows({ ...card, net_lift_n: 0, net_lift_g: Number.NaN }));
    expect(rows["net lift"]).toBe("0.000 N: floats");
  });

  it("writes no sign on a zero, and forces to three places", () => {
    expect(signed(-0.0001, 2)).toBe("0.00");
    expect(signed(0.5, 1)).toBe("+0.5");
    expect(newtons([0, -0.05321, 0])).toBe("0.0532 N");
    expect(newtons([3, 4, 0])).toBe("5.00 N");
    expect(newtons([0, 0, 0])).toBe("0.0000 N");
    expect(newtons([3.9e-15, 0, 0])).toBe("0.0000 N");
    expect(newtons([0, 0.00042, 0])).toBe("0.0004 N");
  });

  it("states the arrows' scale in newtons per metre", () => {
    expect(scaleText(0.25)).toMatch(/^arrow length: 1 m = 0.25 N \(10 cm = 0.025 N\)/);
  });
});
