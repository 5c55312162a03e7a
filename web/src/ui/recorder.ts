// Recording a clip (key R, the panel's record button): the browser's own
// MediaRecorder on the canvas's stream, as WebM (VP9 where the browser
// encodes it, else VP8). The canvas holds only the 3D view (the HUD, the
// panel and the help line are page elements above it), so the clip has none
// of them. A red dot and the elapsed time show while it records, outside the
// canvas; stopping downloads `up-<date>.webm`. The canvas's stream carries a
// frame only when the page draws one, so a page drawing slower than the clip
// is long may give the encoder nothing: such a clip is never saved as an
// empty file, the page says why instead.

import { downloadBlob, timestampName } from "../render/photo/download";

/** Frames per second asked of the canvas's stream (it sends fewer when the page draws fewer). */
const STREAM_FPS = 30;
/** Encoder bit rate, bits/s: balloons against a plain room compress well. */
const BITS_PER_SECOND = 8_000_000;
/** A chunk of the recording is handed over this often, ms, so a long clip is not held in the encoder. */
const CHUNK_MS = 1000;

/** The encoder stops this long after it is asked to, ms, so the last frame drawn is in the clip. */
const STOP_GRACE_MS = 250;

/** WebM types in order of preference; the first the browser records is used. */
export const WEBM_TYPES = ["video/webm;codecs=vp9", "video/webm;codecs=vp8", "video/webm"];

/** The first of `types` that `supported` accepts, or null. */
export function pickType(types: string[], supported: (type: string) => boolean): string | null {
  return types.find((t) => supported(t)) ?? null;
}

/** "0:07", "1:02:03": elapsed seconds as the indicator shows them. */
export function formatElapsed(seconds: number): string {
  const s = Math.max(0, Math.floor(seconds));
  const h = Math.floor(s / 3600);
  const m = Math.floor((s % 3600) / 60);
  const pad = (n: number) => String(n).padStart(2, "0");
  return h > 0 ? `${h}:${pad(m)}:${pad(s % 60)}` : `${m}:${pad(s % 60)}`;
}

/** What the page says when a clip has no frames, instead of saving an empty file. */
export const EMPTY_CLIP_MESSAGE =
  "The clip is empty, nothing was saved: the page drew no frame while it recorded (it draws slowly here). Record for longer.";

/** What a clip needs of a MediaRecorder (the tests give a fake one). */
export type ClipEncoder = Pick<MediaRecorder, "state" | "ondataavailable" | "onstop" | "start" | "requestData" | "stop">;

/** How a take ended: the clip, or why there is none. */
export type ClipResult = { clip: Blob } | { empty: string };

/**
 * One recording: the encoder hands over a chunk every CHUNK_MS, and the rest
 * when the take stops (STOP_GRACE_MS later, so the frame drawn last is in);
 * once it has stopped, the chunks make the clip, or, when there are none,
 * the take ends empty (never a 0-byte file).
 */
export class ClipTake {
  private readonly chunks: Blob[] = [];
  private stopping = false;

  constructor(
    private readonly encoder: ClipEncoder,
    private readonly done: (result: ClipResult) => void,
    private readonly graceMs = STOP_GRACE_MS,
  ) {
    encoder.ondataavailable = (e) => {
      if (e.data.size > 0) this.chunks.push(e.data);
    };
    encoder.onstop = () => this.finish();
    encoder.start(CHUNK_MS);
  }

  /** Stops; `done` follows once the encoder has handed over its last chunk. */
  stop(): void {
    if (this.stopping || this.encoder.state === "inactive") return;
    this.stopping = true;
    // What the encoder holds now comes out before it stops: a clip stopped right after its one frame keeps it.
    this.encoder.requestData();
    // A frame drawn just now reaches the encoder a moment later: stopped at once, the
    // clip of one frame came out empty in Chromium; 100 ms was enough there.
    setTimeout(() => this.encoder.stop(), this.graceMs);
  }

  private finish(): void {
    const clip = new Blob(this.chunks, { type: "video/webm" });
    this.chunks.length = 0;
    this.done(clip.size > 0 ? { clip } : { empty: EMPTY_CLIP_MESSAGE });
  }
}

export class ClipRecorder {
  private take: ClipTake | null = null;
  private started = 0;
  private timer: ReturnType<typeof setInterval> | null = null;
  private readonly indicator: HTMLElement;
  private readonly time: HTMLElement;
  /** Clips saved (for the tests), and the last one's type and size. */
  saved: { type: string; bytes: number }[] = [];
  /** Takes that ended with no frames, so saved nothing (for the tests). */
  empty = 0;

  constructor(
    private readonly canvas: HTMLCanvasElement,
    private readonly changed: (recording: boolean) => void,
    private readonly error: (message: string) => void,
  ) {
    this.indicator = document.createElement("div");
    this.indicator.id = "recording";
    this.indicator.hidden = true;
    this.indicator.innerHTML = `<span class="rec-dot"></span><span class="rec-time">0:00</span>`;
    this.time = this.indicator.querySelector(".rec-time")!;
    // Stacked above the help line (index.html's band), clear of the plots and the panel.
    (document.getElementById("bottom-band") ?? document.body).appendChild(this.indicator);
  }

  get recording(): boolean {
    return this.take !== null;
  }

  toggle(): void {
    if (this.take) this.stop();
    else this.start();
  }

  start(): void {
    if (this.take) return;
    const type = typeof MediaRecorder === "undefined" ? null : pickType(WEBM_TYPES, (t) => MediaRecorder.isTypeSupported(t));
    if (!type) {
      this.error("This browser cannot record the view as WebM (no MediaRecorder for video/webm).");
      return;
    }
    const stream = this.canvas.captureStream(STREAM_FPS);
    const encoder = new MediaRecorder(stream, { mimeType: type, videoBitsPerSecond: BITS_PER_SECOND });
    this.take = new ClipTake(encoder, (result) => {
      stream.getTracks().forEach((t) => t.stop());
      if ("empty" in result) {
        this.empty++;
        this.error(result.empty);
        return;
      }
      this.saved.push({ type: result.clip.type, bytes: result.clip.size });
      downloadBlob(result.clip, timestampName("up", "webm"));
    });
    this.started = performance.now();
    this.time.textContent = formatElapsed(0);
    this.indicator.hidden = false;
    this.timer = setInterval(() => (this.time.textContent = formatElapsed((performance.now() - this.started) / 1000)), 250);
    this.changed(true);
  }

  /** Stops; the clip downloads once the encoder has handed over its last chunk (or the page says it has none). */
  stop(): void {
    const take = this.take;
    if (!take) return;
    this.take = null;
    take.stop();
    if (this.timer) clearInterval(this.timer);
    this.timer = null;
    this.indicator.hidden = true;
    this.changed(false);
  }
}
