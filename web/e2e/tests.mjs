// The end-to-end tests, run by run.mjs against the built app. Each gets a
// fresh page and returns normally on success; `check` throws on failure.

import assert from "node:assert/strict";
import { join } from "node:path";
import { base64url } from "./browser.mjs";

const DEFAULT_BALLOONS = 50;

/** Opens the app (with `hash`) and waits until it has drawn balloons. */
async function open(page, url, hash = "", timeout = 60_000) {
  await page.goto(url + hash);
  await page.waitForFunction(() => window.__up?.ready(), null, { timeout, polling: 250 });
}

const up = (page, expr, arg) => page.evaluate(expr, arg);
const count = (page) => up(page, () => window.__up.balloonCount());
const meanY = (page) =>
  up(page, () => {
    const p = window.__up.poses();
    let sum = 0;
    for (let i = 1; i < p.length; i += 7) sum += p[i];
    return sum / Math.max(1, p.length / 7);
  });

async function pause(page) {
  await page.keyboard.press(" ");
  await page.waitForFunction(() => window.__up.paused());
  // Let OrbitControls' damping settle and the last frame arrive.
  await page.waitForTimeout(600);
}

export const tests = [
  {
    name: "page loads with no console errors",
    async run({ page, url, consoleErrors }) {
      await open(page, url);
      await page.waitForTimeout(1500);
      assert.deepEqual(consoleErrors, []);
      assert.equal(await page.locator("#fatal").isHidden(), true, "no fatal message");
      assert.equal(await page.locator("#message").isHidden(), true, "no error banner");
      assert.match(await page.locator("#hud-count").textContent(), /^Balloons: 50$/);
      await page.waitForFunction(() => /Physics: \d/.test(document.querySelector("#hud-physics").textContent));
      assert.match(await page.locator("#hud-fps").textContent(), /^FPS: \d+/);
    },
  },
  {
    name: "canvas is not blank and shows balloons",
    async run({ page, url, out }) {
      await open(page, url);
      await page.waitForTimeout(2500);
      const withBalloons = await up(page, () => window.__up.pixelStats(false));
      const without = await up(page, () => window.__up.pixelStats(true));
      await page.screenshot({ path: join(out, "default-view.png") });
      assert.ok(withBalloons.std > 12, `the picture varies (std ${withBalloons.std.toFixed(1)})`);
      assert.ok(withBalloons.saturatedFraction > 0.004, `balloon colours on screen (${(withBalloons.saturatedFraction * 100).toFixed(2)} %)`);
      assert.ok(
        withBalloons.saturatedFraction > without.saturatedFraction * 2 + 0.002,
        `hiding the balloons removes the colour (${withBalloons.saturatedFraction} vs ${without.saturatedFraction})`,
      );
    },
  },
  {
    name: "balloons rise over time",
    async run({ page, url }) {
      // A 30 m tall room: the rise takes ≈ 17 s, so a page that was slow to
      // become ready (a loaded machine) still catches the balloons rising.
      const tall = { room: { wall_height: 30 }, balloons: [{ count: 20 }] };
      await open(page, url, `#scene=${base64url(JSON.stringify(tall))}`);
      const before = await meanY(page);
      const stepsBefore = await up(page, () => window.__up.steps());
      await page.waitForTimeout(2500);
      const after = await meanY(page);
      const steps = (await up(page, () => window.__up.steps())) - stepsBefore;
      assert.ok(steps > 20, `the simulation runs (${steps} steps)`);
      assert.ok(after > before + 0.3, `mean height rose from ${before.toFixed(2)} to ${after.toFixed(2)} m`);
    },
  },
  {
    name: "arrow keys orbit the view at constant distance",
    async run({ page, url }) {
      await open(page, url);
      await pause(page);
      // The HUD's FPS changes on its own: compare the 3D view only.
      await page.addStyleTag({ content: "#hud, #help { visibility: hidden !important; }" });
      const still1 = await page.screenshot();
      const still2 = await page.screenshot();
      assert.ok(still1.equals(still2), "paused, the view is still");
      const cam0 = await up(page, () => window.__up.camera());
      await page.keyboard.down("ArrowLeft");
      await page.waitForTimeout(500);
      await page.keyboard.up("ArrowLeft");
      await page.keyboard.down("ArrowUp");
      await page.waitForTimeout(300);
      await page.keyboard.up("ArrowUp");
      await page.waitForTimeout(200);
      const cam1 = await up(page, () => window.__up.camera());
      const moved = await page.screenshot();
      assert.ok(!moved.equals(still2), "the screenshots differ");
      const dist = (c) => Math.hypot(...c.position.map((x, i) => x - c.target[i]));
      assert.ok(Math.abs(dist(cam1) - dist(cam0)) < 1e-3, `distance kept: ${dist(cam0)} → ${dist(cam1)}`);
      assert.ok(cam1.position[1] > cam0.position[1], "up raised the camera");
      const az = (c) => Math.atan2(c.position[0] - c.target[0], c.position[2] - c.target[2]);
      assert.ok(az(cam1) < az(cam0) - 0.02, `left turned the azimuth: ${az(cam0)} → ${az(cam1)}`);
    },
  },
  {
    name: "CTRL then a click adds exactly one balloon at the clicked spot",
    async run({ page, url, out }) {
      await open(page, url);
      await page.keyboard.press("Control");
      await page.waitForFunction(() => window.__up.placement() && window.__up.paused());
      await page.waitForTimeout(300);
      await page.screenshot({ path: join(out, "placement-mode.png") });
      const n = await count(page);
      const target = { x: 1.2, z: -0.9 };
      const pixel = await up(page, (t) => window.__up.project(t.x, 0, t.z), target);
      await page.mouse.click(pixel.x, pixel.y);
      await page.waitForFunction((m) => window.__up.balloonCount() === m, n + 1);
      await page.waitForTimeout(700);
      assert.equal(await count(page), n + 1, "exactly one balloon added");
      const pose = await up(page, () => window.__up.poses().slice(-7));
      assert.ok(Math.hypot(pose[0] - target.x, pose[2] - target.z) < 0.05, `placed at (${pose[0].toFixed(3)}, ${pose[2].toFixed(3)})`);
      assert.ok(pose[1] < 0.5, `on the floor (y = ${pose[1].toFixed(3)})`);
      await page.keyboard.press("Control");
      await page.waitForFunction(() => !window.__up.placement() && !window.__up.paused());
    },
  },
  {
    name: "a change in the panel takes effect",
    async run({ page, url }) {
      await open(page, url);
      const input = page.locator('[data-key="count"] input').first();
      await input.fill("12");
      await input.press("Enter");
      await page.waitForFunction(() => window.__up.balloonCount() === 12, null, { timeout: 30_000 });
      await page.waitForFunction(() => document.querySelector("#hud-count").textContent === "Balloons: 12");
      assert.match(page.url(), /#scene=/, "the scene is in the link");
      const scene = JSON.parse(await up(page, () => window.__up.sceneJson()));
      assert.equal(scene.balloons.reduce((s, g) => s + g.count, 0), 12);
    },
  },
  {
    name: "a shared link loads its scene",
    async run({ page, url }) {
      const scene = { room: { width: 4, depth: 4, wall_height: 2.5, ceiling: "flat" }, balloons: [{ count: 9, colors: ["blue", "#ff8800"] }] };
      await open(page, url, `#scene=${base64url(JSON.stringify(scene))}`);
      assert.equal(await count(page), 9);
      assert.equal(await page.locator("#message").isHidden(), true);
    },
  },
  {
    name: "a malformed shared link shows an error and the default scene",
    async run({ page, url, out }) {
      await open(page, url, "#scene=%%%this-is-not-a-scene");
      await page.locator("#message").waitFor({ state: "visible" });
      assert.match(await page.locator("#message").textContent(), /shared link.*default scene/);
      assert.equal(await count(page), DEFAULT_BALLOONS);
      await page.screenshot({ path: join(out, "malformed-link.png") });
      // A fresh document: a hash-only change would not reload the app.
      await page.goto("about:blank");

      await open(page, url, `#scene=${base64url(JSON.stringify({ room: { width: -1 } }))}`);
      await page.locator("#message").waitFor({ state: "visible" });
      assert.match(await page.locator("#message").textContent(), /room\.width/);
      assert.equal(await count(page), DEFAULT_BALLOONS);
    },
  },
  {
    name: "the debug view draws the contact points, and only while it is on",
    async run({ page, url, out }) {
      // Sleeping balloons report no contacts: keep them awake.
      await open(page, url, `#scene=${base64url(JSON.stringify({ sim: { sleep: false } }))}`);
      await page.waitForFunction(() => (window.__up.stats()?.stats.contacts ?? 0) > 0, null, { timeout: 30_000 });
      assert.equal((await up(page, () => window.__up.contacts())).inFrame, 0, "no contacts travel while the debug view is off");
      await page.keyboard.press("d");
      await page.waitForFunction(() => window.__up.contacts().drawn > 0, null, { timeout: 20_000 });
      await pause(page);
      const c = await up(page, () => window.__up.contacts());
      assert.ok(c.drawn > 0, "contacts are drawn");
      assert.equal(c.drawn, c.inFrame, `every contact of the frame is drawn (${c.drawn} of ${c.inFrame})`);
      assert.ok(c.total >= c.inFrame, `the step had ${c.total} contacts`);
      await page.addStyleTag({ content: "#hud, #help { visibility: hidden !important; }" });
      const debugShot = await page.screenshot({ path: join(out, "debug-view.png") });
      await page.keyboard.press("d");
      await page.keyboard.press("n"); // a fresh frame, without contacts
      await page.waitForFunction(() => window.__up.contacts().inFrame === 0 && !window.__up.debugView());
      assert.equal((await up(page, () => window.__up.contacts())).drawn, 0);
      await page.waitForTimeout(300);
      assert.ok(!(await page.screenshot()).equals(debugShot), "the debug view changed the picture");
    },
  },
  {
    name: "the wasm engine answers bad calls with a status and a message, never a trap",
    async run({ page, url }) {
      await page.goto(url + "blank"); // same origin, without starting the app
      // The shipped module itself, in the browser (panics abort there, unlike in native tests).
      const result = await page.evaluate(async () => {
        const bytes = await (await fetch("wasm/up_wasm.wasm")).arrayBuffer();
        const { instance } = await WebAssembly.instantiate(bytes, { env: { up_now_ms: () => performance.now() } });
        const x = instance.exports;
        const message = () => new TextDecoder().decode(new Uint8Array(x.memory.buffer, x.up_last_error_ptr(), x.up_last_error_len()));
        const calls = [];
        const call = (name, ...args) => {
          let code;
          try {
            code = x[name](...args);
          } catch (e) {
            code = `trap: ${e}`;
          }
          calls.push({ name, args: args.map(String), code, message: message() });
        };
        call("up_step", 1);
        call("up_write_poses");
        call("up_add_balloon_on_floor", 0, 0, 0);
        call("up_release");
        const beforeWorld = calls.length;
        call("up_world_default");
        const n = x.up_body_count();
        call("up_add_balloon", NaN, 1, 0, 0, 0);
        call("up_add_balloon", 0, Infinity, 0, 0, 0);
        call("up_set_velocity", 0, 0, -Infinity, 0, 0, 0, 0);
        call("up_drag_to", NaN, NaN, NaN);
        call("up_grab", 0, 0, NaN, 0);
        call("up_remove", n);
        call("up_remove", -1); // u32::MAX on the wasm side
        call("up_grab", n + 3, 0, 1, 0);
        call("up_model_tree", 99);
        call("up_add_balloon", 0, 1, 0, 9999, 0);
        call("up_add_balloon", 1e30, 1, 0, 0, 0);
        call("up_set_velocity", 0, 1e6, 0, 0, 0, 0, 0);
        call("up_step", 1e9);
        call("up_world_from_json", 12345, 10);
        call("up_free", 12345, 10);
        const ok = x.up_step(10);
        return { calls, beforeWorld, ok, count: x.up_body_count(), n };
      });
      for (const [i, c] of result.calls.entries()) {
        if (c.name === "up_world_default") {
          assert.equal(c.code, 0);
          continue;
        }
        assert.equal(typeof c.code, "number", `${c.name}(${c.args}) did not trap: ${c.code}`);
        const expected = i < result.beforeWorld ? [1] : [2, 3];
        assert.ok(expected.includes(c.code), `${c.name}(${c.args}) answered ${c.code}: ${c.message}`);
        assert.ok(c.message.startsWith(`${c.name}: `), `the message names the export: ${c.message}`);
      }
      assert.equal(result.ok, 0, "the engine still steps after every refused call");
      assert.equal(result.count, result.n, "no refused call changed the world");
    },
  },
  {
    name: "the page answers input and keeps drawing while a large scene runs in the worker",
    // SwiftShader on two shared cores draws such a frame in seconds.
    timeoutMs: 180_000,
    async run({ page, url, out }) {
      // 800 balloons: about 10 ms per step in the worker (the crowd geometry draws them).
      const scene = { room: { width: 10, depth: 10 }, balloons: [{ count: 800 }], sim: { sleep: false } };
      // A small canvas: the claim is about the main thread, not about pixels.
      await page.setViewportSize({ width: 480, height: 300 });
      await open(page, url, `#scene=${base64url(JSON.stringify(scene))}`, 120_000);
      assert.equal(await count(page), 800);
      await page.waitForFunction(() => (window.__up.stats()?.stats.stages.at(-1)?.[1] ?? 0) > 1, null, { timeout: 30_000 });
      const before = await up(page, () => ({ steps: window.__up.steps(), frames: window.__up.frames().drawn, camera: window.__up.camera() }));
      // A key handled on the main thread changes state at once...
      await page.keyboard.press("d");
      assert.equal(await up(page, () => window.__up.debugView()), true, "the D key's handler ran");
      await page.keyboard.press("d");
      // ...and a held arrow turns the view at the next frames, whatever the physics costs.
      await page.keyboard.down("ArrowLeft");
      await page.waitForFunction((x) => Math.abs(window.__up.camera().position[0] - x) > 1e-3, before.camera.position[0], { timeout: 30_000 });
      await page.keyboard.up("ArrowLeft");
      // Frames kept coming while the worker stepped.
      await page.waitForFunction((b) => window.__up.frames().drawn >= b.frames + 2 && window.__up.steps() > b.steps + 10, before, { timeout: 30_000 });
      const after = await up(page, () => ({ steps: window.__up.steps(), paused: window.__up.paused() }));
      assert.equal(after.paused, false, "the simulation ran throughout");
      await page.screenshot({ path: join(out, "large-scene.png") });
    },
  },
  {
    name: "a balloon can be grabbed, dragged and popped",
    async run({ page, url }) {
      await open(page, url, `#scene=${base64url(JSON.stringify({ balloons: [{ count: 3 }], sim: { gravity: [0, -9.81, 0] } }))}`);
      await page.waitForTimeout(3000); // let them reach the ceiling and settle a little
      const target = await up(page, () => {
        const c = window.__up.balloonCenter(0);
        return { ...window.__up.project(c[0], c[1], c[2]), c };
      });
      await page.mouse.move(target.x, target.y);
      await page.mouse.down();
      for (let i = 1; i <= 10; i++) {
        await page.mouse.move(target.x + 12 * i, target.y + 15 * i);
        await page.waitForTimeout(60);
      }
      await page.waitForTimeout(600);
      const held = await up(page, () => window.__up.balloonCenter(0));
      await page.mouse.up();
      const moved = Math.hypot(held[0] - target.c[0], held[1] - target.c[1], held[2] - target.c[2]);
      assert.ok(moved > 0.3, `the grabbed balloon followed the mouse (${moved.toFixed(2)} m)`);

      await pause(page);
      const n = await count(page);
      const c = await up(page, () => {
        const p = window.__up.balloonCenter(0);
        return window.__up.project(p[0], p[1], p[2]);
      });
      await page.keyboard.down("Shift");
      await page.mouse.click(c.x, c.y);
      await page.keyboard.up("Shift");
      await page.waitForFunction((m) => window.__up.balloonCount() === m, n - 1);
    },
  },
];
