// The shipped wasm module itself, in the browser (panics abort there, unlike
// in native tests): bad calls answer with a status and a message.

import { expect, test } from "./fixtures";

interface Call {
  name: string;
  args: string[];
  code: number | string;
  message: string;
}

test("the wasm engine answers bad calls with a status and a message, never a trap", async ({ page }) => {
  // A blank page of the app's origin, without starting the app.
  await page.route("**/blank", (route) => route.fulfill({ contentType: "text/html", body: "<!doctype html><title>blank</title>" }));
  await page.goto("blank");
  const result = await page.evaluate(async () => {
    const bytes = await (await fetch("wasm/up_wasm.wasm")).arrayBuffer();
    const { instance } = await WebAssembly.instantiate(bytes, { env: { up_now_ms: () => performance.now() } });
    const x = instance.exports as Record<string, (...args: number[]) => number> & { memory: WebAssembly.Memory };
    const message = () => new TextDecoder().decode(new Uint8Array(x.memory.buffer, x.up_last_error_ptr(), x.up_last_error_len()));
    const calls: Call[] = [];
    const call = (name: string, ...args: number[]) => {
      let code: number | string;
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
      expect(c.code, c.message).toBe(0);
      continue;
    }
    expect(typeof c.code, `${c.name}(${c.args}) did not trap: ${c.code}`).toBe("number");
    const expected = i < result.beforeWorld ? [1] : [2, 3];
    expect(expected, `${c.name}(${c.args}) answered ${c.code}: ${c.message}`).toContain(c.code);
    expect(c.message, "the message names the export").toMatch(new RegExp(`^${c.name}: `));
  }
  expect(result.ok, "the engine still steps after every refused call").toBe(0);
  expect(result.count, "no refused call changed the world").toBe(result.n);
});
