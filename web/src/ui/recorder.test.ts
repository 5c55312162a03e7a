import { describe, expect, it } from "vitest";
import { formatElapsed, pickType, WEBM_TYPES } from "./recorder";
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
