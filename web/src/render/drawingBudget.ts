// What the live view spends on a frame, by device: a phone or a tablet (a
// touch screen no wider than a tablet's) draws for less — a quarter of the
// shadow map's texels, at most 1.5 device pixels per CSS pixel, and the
// crowd's lighter balloon mesh (crowdLod.ts) from fewer balloons on — and the
// page lowers that count further while it measures frames slower than it
// should. The HUD says what was left out (`costText`).

import { CROWD_BALLOONS } from "./crowdLod";

/** What the page knows of the device before it draws. */
export interface DeviceTraits {
  /** `(pointer: coarse)`: the primary pointer is a finger. */
  coarsePointer: boolean;
  /** The screen's shorter side, CSS px. */
  screenShortSide: number;
}

export interface DrawingBudget {
  /** Whether anything is drawn for less than on a desktop. */
  lighter: boolean;
  /** The key light's shadow map, texels on a side. */
  shadowMapSize: number;
  /** Most device pixels per CSS pixel drawn. */
  pixelRatioCap: number;
  /** Balloons above which the lighter crowd mesh draws them. */
  crowdAbove: number;
}

/** A touch screen whose shorter side is under this (CSS px) is a phone or a tablet: the largest tablets are 1,024 across. */
export const SMALL_SCREEN_SIDE = 1100;

export const FULL_BUDGET: DrawingBudget = { lighter: false, shadowMapSize: 2048, pixelRatioCap: 2, crowdAbove: CROWD_BALLOONS };

/**
 * The lighter budget. Its crowd count is a starting point, a third of the
 * desktop's: SwiftShader's draws on the test machines say nothing of a
 * phone's GPU (docs/perf-log.md), so the count the page keeps is the one
 * `CrowdGovernor` picks by measuring the device's own frames.
 */
export const LIGHT_BUDGET: DrawingBudget = { lighter: true, shadowMapSize: 1024, pixelRatioCap: 1.5, crowdAbove: 150 };

export function drawingBudget(device: DeviceTraits): DrawingBudget {
  return device.coarsePointer && device.screenShortSide < SMALL_SCREEN_SIDE ? { ...LIGHT_BUDGET } : { ...FULL_BUDGET };
}

/** The HUD's line for a lighter budget ("Drawing for less: shadows 1024², ≤ 1.5 px/px, simple balloons above 150"); null for the full one. */
export function costText(b: DrawingBudget): string | null {
  if (!b.lighter) return null;
  return `Drawing for less: shadows ${b.shadowMapSize}², ≤ ${b.pixelRatioCap} px/px, simple balloons above ${b.crowdAbove}`;
}

/** Frames measured before judging (the first ones carry shader compiles and the model's upload). */
export const WARMUP_FRAMES = 30;
/** Frames judged at a time. */
export const JUDGED_FRAMES = 60;
/** Frames slower than this on average (ms; under 30 per second) lower the crowd count. */
export const SLOW_FRAME_MS = 1000 / 30;
/** An interval longer than this (ms) is a hidden tab or a stall, not a frame's cost: left out. */
export const STALL_MS = 250;

/**
 * Lowers the crowd count by measurement: while the full balloon mesh is
 * drawn, frames slower than `SLOW_FRAME_MS` on average over `JUDGED_FRAMES`
 * move the count to just under the balloons shown, so the crowd mesh draws
 * them. It never raises the count: a page that was slow stays light.
 */
export class CrowdGovernor {
  private seen = 0;
  private sum = 0;
  private judged = 0;

  constructor(public crowdAbove: number) {}

  /**
   * One frame `intervalMs` after the last with `count` balloons; returns the
   * new crowd count when it lowers it, else null.
   */
  frame(intervalMs: number, count: number): number | null {
    this.seen++;
    // The crowd mesh already draws them, or too few to matter, or a stall: nothing to judge.
    if (this.seen <= WARMUP_FRAMES || count <= 1 || count > this.crowdAbove || !(intervalMs < STALL_MS)) return null;
    this.sum += intervalMs;
    this.judged++;
    if (this.judged < JUDGED_FRAMES) return null;
    const mean = this.sum / this.judged;
    this.sum = 0;
    this.judged = 0;
    if (mean <= SLOW_FRAME_MS) return null;
    this.crowdAbove = count - 1;
    return this.crowdAbove;
  }
}
