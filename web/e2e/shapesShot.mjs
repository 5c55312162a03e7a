// Screenshots of the foil shapes (a heart, a star, a "3" and a "0") in the
// real app, headless: `node e2e/shapesShot.mjs OUT_DIR` after `npm run build`.
// Each balloon hangs on a weighted ribbon at eye height, facing the camera.

import { join } from "node:path";
import { base64url, launchChromium, TEST_PATH } from "./browser.mjs";
import { serveDist } from "./serve.mjs";

const out = process.argv[2] ?? ".";
const ribbon = { length_m: 0.9, weight_g: 40 };
const at = (x) => ({ min: [x - 0.5, 1.3, -0.5], max: [x + 0.5, 2.3, 0.5] });
const scene = {
  room: { width: 6, depth: 6, wall_height: 3.5, ceiling: "flat" },
  balloons: [
    { count: 1, kind: "foil", shape: "heart", size_in: 18, colors: ["red"], tilt_deg: 0, yaw_deg: 0, spawn: at(-1.8), ribbon },
    { count: 1, kind: "foil", shape: "star", size_in: 20, colors: ["#d4af37"], tilt_deg: 0, yaw_deg: 0, spawn: at(-0.6), ribbon },
    { count: 1, kind: "foil", shape: "digit", text: "3", size_in: 34, colors: ["blue"], tilt_deg: 0, yaw_deg: 0, spawn: at(0.6), ribbon },
    { count: 1, kind: "foil", shape: "digit", text: "0", size_in: 34, colors: ["#c0c0c0"], tilt_deg: 0, yaw_deg: 0, spawn: at(1.8), ribbon },
  ],
};
const server = await serveDist();
const browser = await launchChromium();
try {
  const page = await browser.newPage({ viewport: { width: 1280, height: 720 }, deviceScaleFactor: 2 });
  page.on("console", (m) => m.type() === "error" && console.error("page:", m.text()));
  await page.goto(server.url + TEST_PATH + `#scene=${base64url(JSON.stringify(scene))}`);
  await page.waitForFunction(() => window.__up?.ready(), null, { timeout: 90_000 });
  for (const [name, wait] of [["shapes-2s", 2000], ["shapes-8s", 6000]]) {
    await page.waitForTimeout(wait);
    const file = join(out, `${name}.png`);
    await page.screenshot({ path: file });
    // The balloons alone, close up.
    await page.screenshot({ path: join(out, `${name}-close.png`), clip: { x: 440, y: 360, width: 440, height: 130 } });
    console.log(`screenshot: ${file}`, JSON.stringify(await page.evaluate(() => window.__up.foil())));
  }
} finally {
  await browser.close();
  await server.close();
}
