import { describe, expect, it } from "vitest";
import { ClipTake, EMPTY_CLIP_MESSAGE, formatElapsed, pickType, WEBM_TYPES, type ClipEncoder, type ClipResult } from "./recorder";
import { timestampName } from "../render/photo/download";

describe("recorder", () => {
  it("prefers VP9, then VP8, then plain WebM", () => {
    expect(pickType(WEBM_TYPES, () => true)).toBe("video/webm;codecs=vp9");
    expect(pickType(WEBM_TYPES, (t) => !t.includes("vp9"))).toBe("video/webm;codecs=vp8");
    expect(pickType(WEBM_TYPES, (t) => t === "video/webm")).toBe("video/webm");
    expect(pickType(WEBM_TYPES, () => false)).toBeNull();
  });

  it("shows elapsed time as m:ss, and h:mm:ss past an hour", () => {
    expect(formatElapsed(0)).toBe("0:00");
    expect(formatElapsed(7.9)).toBe("0:07");
    expect(formatElapsed(62)).toBe("1:02");
    expect(formatElapsed(3723)).toBe("1:02:03");
  });

  it("names files with the local date and time, no characters a file system refuses", () => {
    const name = timestampName("up", "webm", new Date(2026, 11, 2, 3, 4, 5));
    expect(name).toBe("up-2026-12-02T03-04-05.webm");
  });
});

/**
 * A MediaRecorder as a slow page gives it: each drawn frame is encoded into
 * bytes the encoder holds until a timeslice ends or it is asked for them
 * (requestData); stopping hands over only what was asked for before, then
 * ends (asynchronously, as the browser's does). The worst case of a frame
 * drawn just before the clip stops.
 */
class HoldingEncoder implements ClipEncoder {
  state: RecordingState = "inactive";
  ondataavailable: ClipEncoder["ondataavailable"] = null;
  onstop: ClipEncoder["onstop"] = null;
  timeslice: number | undefined;
  private held = 0;

  start(timeslice?: number): void {
    this.timeslice = timeslice;
    this.state = "recording";
  }
  /** The page draws a frame: `bytes` of it enter the encoder. */
  frame(bytes = 2000): void {
    if (this.state === "recording") this.held += bytes;
  }
  /** A timeslice ends: what is held comes out (nothing, when no frame came). */
  sliceEnds(): void {
    if (this.timeslice !== undefined) this.requestData();
  }
  requestData(): void {
    const data = new Blob([new Uint8Array(this.held)], { type: "video/webm" });
    this.held = 0;
    this.ondataavailable?.call(this as unknown as MediaRecorder, { data } as BlobEvent);
  }
  stop(): void {
    this.held = 0;
    this.state = "inactive";
    queueMicrotask(() => this.onstop?.call(this as unknown as MediaRecorder, new Event("stop")));
  }
}

/** Starts a take on `encoder`, lets `record` drive it, stops it, and resolves with how it ended. */
async function take(encoder: HoldingEncoder, record: () => void): Promise<ClipResult> {
  const ended = new Promise<ClipResult>((resolve) => {
    // No grace: the fake's frames are in the encoder at once.
    const clip = new ClipTake(encoder, resolve, 0);
    record();
    clip.stop();
  });
  return ended;
}

describe("clip takes", () => {
  it("record with a timeslice, so a long clip comes out in chunks", async () => {
    const encoder = new HoldingEncoder();
    const result = await take(encoder, () => {
      for (let s = 0; s < 3; s++) {
        encoder.frame(1000);
        encoder.sliceEnds();
      }
    });
    expect(encoder.timeslice).toBeGreaterThan(0);
    expect("clip" in result && result.clip.size).toBe(3000);
  });

  it("keep a frame drawn just before the stop: a clip of one frame is not empty", async () => {
    const encoder = new HoldingEncoder();
    const result = await take(encoder, () => encoder.frame(1500));
    expect("clip" in result && result.clip.size).toBe(1500);
    expect("clip" in result && result.clip.type).toBe("video/webm");
  });

  it("end with the page's explanation, not a 0-byte clip, when no frame was drawn", async () => {
    const encoder = new HoldingEncoder();
    const result = await take(encoder, () => {
      encoder.sliceEnds();
      encoder.sliceEnds();
    });
    expect(result).toEqual({ empty: EMPTY_CLIP_MESSAGE });
  });

  it("never hand over an empty clip, however frames and slices fall", async () => {
    for (let frames = 0; frames < 4; frames++) {
      for (let slices = 0; slices < 3; slices++) {
        const encoder = new HoldingEncoder();
        const result = await take(encoder, () => {
          for (let k = 0; k < Math.max(frames, slices); k++) {
            if (k < frames) encoder.frame();
            if (k < slices) encoder.sliceEnds();
          }
        });
        if (frames === 0) expect(result, `${frames} frames, ${slices} slices`).toEqual({ empty: EMPTY_CLIP_MESSAGE });
        else expect("clip" in result && result.clip.size, `${frames} frames, ${slices} slices`).toBe(frames * 2000);
      }
    }
  });
});
