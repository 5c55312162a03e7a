// Recording a clip (key R, the panel's record button): the browser's own
// MediaRecorder on the canvas's stream, as WebM (VP9 where the browser
// encodes it, else VP8). The canvas holds only the 3D view (the HUD, the
// panel and the help line are page elements above it), so the clip has none
// of them. A red dot and the elapsed time show while it records, outside the
// canvas; stopping downloads `up-<date>.webm`.

import { downloadBlob, timestampName } from "../render/photo/download";

/** Frames per second asked of the canvas's stream (it sends fewer when the page draws fewer). */
const STREAM_FPS = 30;
/** Encoder bit rate, bits/s: balloons against a plain room compress well. */
const BITS_PER_SECOND = 8_000_000;
/** A chunk of the recording is handed over this often, ms, so a long clip is not held in the encoder. */
const CHUNK_MS = 1000;

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

export class ClipRecorder {
  private recorder: MediaRecorder | null = null;
  private chunks: Blob[] = [];
  private started = 0;
  private timer: ReturnType<typeof setInterval> | null = null;
  private readonly indicator: HTMLElement;
  private readonly time: HTMLElement;
  /** Clips saved (for the tests), and the last one's type and size. */
  saved: { type: string; bytes: number }[] = [];

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
    return this.recorder !== null;
  }

  toggle(): void {
    if (this.recorder) this.stop();
    else this.start();
  }

  start(): void {
    if (this.recorder) return;
    const type = typeof MediaRecorder === "undefined" ? null : pickType(WEBM_TYPES, (t) => MediaRecorder.isTypeSupported(t));
    if (!type) {
      this.error("This browser cannot record the view as WebM (no MediaRecorder for video/webm).");
      return;
    }
    const stream = this.canvas.captureStream(STREAM_FPS);
    const recorder = new MediaRecorder(stream, { mimeType: type, videoBitsPerSecond: BITS_PER_SECOND });
    this.chunks = [];
    recorder.ondataavailable = (e) => {
      if (e.data.size > 0) this.chunks.push(e.data);
    };
    recorder.onstop = () => {
      stream.getTracks().forEach((t) => t.stop());
      const blob = new Blob(this.chunks, { type: "video/webm" });
      this.chunks = [];
      this.saved.push({ type: blob.type, bytes: blob.size });
      downloadBlob(blob, timestampName("up", "webm"));
    };
    recorder.start(CHUNK_MS);
    this.recorder = recorder;
    this.started = performance.now();
    this.time.textContent = formatElapsed(0);
    this.indicator.hidden = false;
    this.timer = setInterval(() => (this.time.textContent = formatElapsed((performance.now() - this.started) / 1000)), 250);
    this.changed(true);
  }

  /** Stops; the clip downloads once the encoder has handed over its last chunk. */
  stop(): void {
    const recorder = this.recorder;
    if (!recorder) return;
    this.recorder = null;
    recorder.stop();
    if (this.timer) clearInterval(this.timer);
    this.timer = null;
    this.indicator.hidden = true;
    this.changed(false);
  }
}
