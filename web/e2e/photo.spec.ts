// Photo mode and clip recording, as a user does them: P pauses and path-traces
// the scene drawn now until the samples add up, the picture is not the live
// frame, save downloads a PNG of the canvas's size, and P again resumes the
// simulation; R records the view and R again downloads a WebM clip, which is
// never an empty file, however slowly the page draws.
//
// SwiftShader traces on the CPU: the photo test runs in a small page (its
// cost is per pixel) with a generous bound, and writes how long each part
// took into the report's annotations (measurements, not limits).

import { readFileSync } from "node:fs";
import type { Page } from "@playwright/test";
import { expect, open, test } from "./fixtures";

/** The photo test's page: small, since every sample costs SwiftShader per pixel. */
const PHOTO_VIEWPORT = { width: 320, height: 200 };
/** Samples the photo must reach. */
const SAMPLES = 16;
/**
 * Least mean absolute RGB difference (0–255) between the photo and the live
 * frame just before it. Two live frames of a paused scene differ by the
 * noise floor, asserted below 1 (a raster of a still scene is the same
 * picture); a path-traced picture of the same scene, lit by traced light
 * rather than shadow maps and an environment map, differs by far more (the
 * measured value is in the annotations). 4 is well above the floor and
 * well below what a re-lit picture gives.
 */
const MIN_DIFFERENCE = 4;

const PNG_SIGNATURE = [0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a];
const EBML_MAGIC = [0x1a, 0x45, 0xdf, 0xa3];

test.use({ viewport: PHOTO_VIEWPORT });

test("P path-traces the scene, save downloads a PNG of the canvas's size, P again resumes", async ({ page }, testInfo) => {
  // The tracer's shader compiles once, on the page's one GPU thread: in
  // SwiftShader on a loaded two-core machine that alone has taken minutes.
  test.setTimeout(40 * 60_000);
  const note = (type: string, description: string) => testInfo.annotations.push({ type, description });
  await open(page);
  await page.waitForTimeout(2000);

  // The noise floor: two live frames of the paused scene.
  await page.keyboard.press(" ");
  await page.waitForFunction(() => window.__up!.paused());
  await page.waitForTimeout(600);
  await page.evaluate(() => window.__up!.keepPixels("still-a"));
  await page.waitForTimeout(300);
  await page.evaluate(() => window.__up!.keepPixels("still-b"));
  const floor = await page.evaluate(() => window.__up!.pixelDifference("still-a", "still-b"));
  note("noise floor (paused live frames)", floor.toFixed(3));
  expect(floor).toBeLessThan(1);
  await page.keyboard.press(" ");
  await page.waitForFunction(() => !window.__up!.paused());

  // The live frame, then P.
  const live = await page.evaluate(() => window.__up!.keepPixels("live"));
  const pressed = Date.now();
  await page.keyboard.press("p");
  await page.waitForFunction(() => window.__up!.photo().active, null, { timeout: 30 * 60_000, polling: 1000 });
  expect(await page.evaluate(() => window.__up!.paused()), "photo mode pauses the simulation").toBe(true);
  await page.waitForFunction(() => window.__up!.photo().samples >= 1, null, { timeout: 30 * 60_000, polling: 1000 });
  note("seconds from P to the first sample", ((Date.now() - pressed) / 1000).toFixed(1));
  const firstSample = Date.now();
  await page.waitForFunction((n) => window.__up!.photo().samples >= n, SAMPLES, { timeout: 30 * 60_000, polling: 1000 });
  note(`seconds from the first sample to ${SAMPLES}`, ((Date.now() - firstSample) / 1000).toFixed(1));
  const { bake, samples } = await page.evaluate(() => window.__up!.photo());
  note("bake (ms in all, ms merging, instances, triangles)", `${bake.ms.toFixed(0)}, ${bake.mergeMs.toFixed(0)}, ${bake.instances}, ${bake.triangles}`);
  expect(bake.instances, "the balloons and their ribbons are in the photo").toBeGreaterThanOrEqual(50);
  await expect(page.locator("#hud-photo")).toContainText(/Photo: \d+ samples/);

  const photo = await page.evaluate(() => window.__up!.keepPixels("photo"));
  const difference = await page.evaluate(() => window.__up!.pixelDifference("live", "photo"));
  note("photo against the live frame (mean |ΔRGB|)", difference.toFixed(2));
  note("mean luminance, live and photo", `${live.mean.toFixed(1)}, ${photo.mean.toFixed(1)}`);
  expect(difference).toBeGreaterThan(MIN_DIFFERENCE);
  // Neither black nor broken (NaN samples come out black).
  expect(photo.mean).toBeGreaterThan(20);
  expect(photo.black).toBeLessThan(0.05);
  await testInfo.attach(`photo, ${samples}+ samples`, { body: await page.screenshot(), contentType: "image/png" });

  // Save: a PNG of the canvas's size.
  // Each frame traces a tile: the click alone has taken 30 s here.
  // A window this small has the compact layout: the panel is folded behind its title until opened.
  await page.locator(".lil-gui.lil-root > .lil-title").click({ timeout: 180_000 });
  const downloading = page.waitForEvent("download", { timeout: 180_000 });
  await page.locator('[data-key="savePhoto"] button').click({ timeout: 180_000 });
  const download = await downloading;
  expect(download.suggestedFilename()).toMatch(/^up-photo-.*\.png$/);
  const pngPath = (await download.path())!;
  await testInfo.attach("saved photo", { path: pngPath, contentType: "image/png" });
  const png = readFileSync(pngPath);
  expect(Array.from(png.subarray(0, 8))).toEqual(PNG_SIGNATURE);
  // IHDR: width and height, big-endian, right after the signature and the chunk's length and type.
  expect(png.readUInt32BE(16)).toBe(photo.width);
  expect(png.readUInt32BE(20)).toBe(photo.height);

  // P again: the live view, running again.
  await page.keyboard.press("p");
  await page.waitForFunction(() => !window.__up!.photo().active);
  await page.waitForFunction(() => !window.__up!.paused());
  await expect(page.locator("#hud-photo")).toBeHidden();
  const before = await page.evaluate(() => window.__up!.clock().simTime);
  await page.waitForFunction((t) => window.__up!.clock().simTime > t + 0.2, before, { timeout: 60_000 });
});

test("R records the view for 3 s, R again downloads a WebM clip", async ({ page }, testInfo) => {
  await open(page);
  await page.keyboard.press("r");
  await page.waitForFunction(() => window.__up!.recording().recording);
  await expect(page.locator("#recording")).toBeVisible();
  await page.waitForTimeout(3000);
  const downloading = page.waitForEvent("download");
  await page.keyboard.press("r");
  const download = await downloading;
  await expect(page.locator("#recording")).toBeHidden();
  expect(download.suggestedFilename()).toMatch(/^up-.*\.webm$/);
  const clip = readFileSync((await download.path())!);
  testInfo.annotations.push({ type: "clip bytes", description: String(clip.length) });
  expect(clip.length).toBeGreaterThan(1000);
  expect(Array.from(clip.subarray(0, 4))).toEqual(EBML_MAGIC);
  const saved = await page.evaluate(() => window.__up!.recording().saved);
  expect(saved).toEqual([{ type: "video/webm", bytes: clip.length }]);
});

/**
 * Lets the page draw exactly one frame while its drawing is held (the hook's
 * `holdDrawing`): the page at a frame a second or slower, as a loaded machine
 * without a GPU draws a large scene.
 */
async function drawOneFrame(page: Page): Promise<void> {
  await page.evaluate(
    () =>
      new Promise<void>((resolve) => {
        const up = window.__up!;
        const before = up.frames().drawn;
        up.holdDrawing(false);
        const check = () => {
          if (up.frames().drawn > before) {
            up.holdDrawing(true);
            resolve();
          } else requestAnimationFrame(check);
        };
        requestAnimationFrame(check);
      }),
  );
}

test("a clip on a page drawing a frame a second is never an empty file: it has its frames, or the page says there is nothing to save", async ({ page }, testInfo) => {
  const note = (type: string, description: string) => testInfo.annotations.push({ type, description });
  await open(page);
  const downloads: Buffer[] = [];
  page.on("download", (d) => void d.path().then((p) => p && downloads.push(readFileSync(p))));
  await page.evaluate(() => window.__up!.holdDrawing(true));
  const message = page.locator("#message");

  // Three seconds at a frame a second.
  await page.keyboard.press("r");
  await page.waitForFunction(() => window.__up!.recording().recording);
  for (let s = 0; s < 3; s++) {
    await drawOneFrame(page);
    await page.waitForTimeout(1000);
  }
  const downloading = page.waitForEvent("download");
  await page.keyboard.press("r");
  const clip = readFileSync((await (await downloading).path())!);
  note("3 s clip at a frame a second, bytes", String(clip.length));
  expect(Array.from(clip.subarray(0, 4))).toEqual(EBML_MAGIC);
  expect(clip.length).toBeGreaterThan(1000);

  // Stopped right after its one frame: a clip with it, or the page's word that it has none.
  await page.keyboard.press("r");
  await page.waitForFunction(() => window.__up!.recording().recording);
  await drawOneFrame(page);
  await page.keyboard.press("r");
  await page.waitForFunction(() => {
    const r = window.__up!.recording();
    return r.saved.length + r.empty === 2;
  });
  const afterOne = await page.evaluate(() => window.__up!.recording());
  if (afterOne.empty === 0) {
    note("clip stopped right after one frame", `saved, ${afterOne.saved[1].bytes} bytes`);
    expect(afterOne.saved[1].bytes).toBeGreaterThan(0);
  } else {
    note("clip stopped right after one frame", "nothing to save, the page said so");
    await expect(message).toBeVisible();
    await expect(message).toContainText("nothing was saved");
  }

  // No frame at all: nothing saved, and the page says why.
  await page.keyboard.press("r");
  await page.waitForFunction(() => window.__up!.recording().recording);
  await page.waitForTimeout(2500);
  await page.keyboard.press("r");
  await page.waitForFunction((n) => window.__up!.recording().empty > n, afterOne.empty);
  await expect(message).toBeVisible();
  await expect(message).toContainText("nothing was saved");
  const { saved } = await page.evaluate(() => window.__up!.recording());
  expect(saved.length, "the frameless clip saved nothing").toBe(afterOne.saved.length);
  // Every download the page made has bytes.
  await expect.poll(() => downloads.length).toBe(saved.length);
  expect(downloads.every((d) => d.length > 0)).toBe(true);
  await page.evaluate(() => window.__up!.holdDrawing(false));
});
