// The shipped wasm module and its glue themselves, in the browser (panics
// abort there, unlike in native tests): bad calls throw an Error naming the
// kind and the method, never a trap, and leave the world as it was.

import { expect, test } from "./fixtures";

interface Call {
  name: string;
  args: string;
  /** The thrown error's `name`, or null when the call returned. */
  kind: string | null;
  message: string;
  /** Whether it threw a WebAssembly.RuntimeError (a trap). */
  trap: boolean;
}

test("the wasm engine answers bad calls with an error and a message, never a trap", async ({ page }) => {
  // A blank page of the app's origin, without starting the app.
  await page.route("**/blank", (route) => route.fulfill({ contentType: "text/html", body: "<!doctype html><title>blank</title>" }));
  await page.goto("blank");
  const result = await page.evaluate(async () => {
    const g = await import(new URL("wasm/up_wasm.js", document.baseURI).href);
    g.initSync({ module: await (await fetch("wasm/up_wasm.wasm")).arrayBuffer() });
    const errorKinds: string[] = g.constants().error_kinds;
    const e = new g.Engine();
    const calls: Call[] = [];
    const call = (name: string, ...args: unknown[]) => {
      const record: Call = { name, args: args.map(String).join(", "), kind: null, message: "", trap: false };
      try {
        e[name](...args);
      } catch (err) {
        record.trap = err instanceof WebAssembly.RuntimeError;
        record.kind = err instanceof Error ? err.name : `not an Error: ${String(err)}`;
        record.message = err instanceof Error ? err.message : String(err);
      }
      calls.push(record);
    };
    call("step", 1);
    call("write_poses");
    call("add_balloon_on_floor", 0, 0, 0);
    call("release");
    call("write_model_tree", 0);
    call("grab", 0, 0, 1, 0);
    call("write_ribbon_points");
    call("write_ribbons");
    call("apply_live", { control: "ribbon_length", value: 1 });
    call("grab_ribbon", 0, 1, 0, 1, 0);
    const beforeWorld = calls.length;
    e.load_default_scene();
    const n: number = e.body_count();
    const hash = String(e.state_hash());
    call("add_balloon", NaN, 1, 0, 0, 0);
    call("add_balloon", 0, Infinity, 0, 0, 0);
    call("set_velocity", 0, 0, -Infinity, 0, 0, 0, 0);
    call("apply_impulse", 0, NaN, 0, 0, 0, 1, 0);
    call("drag_to", NaN, NaN, NaN);
    call("grab", 0, 0, NaN, 0);
    call("remove", n);
    call("remove", -1); // u32::MAX on the wasm side
    call("grab", n + 3, 0, 1, 0);
    call("write_model_tree", 99);
    call("add_balloon", 0, 1, 0, 9999, 0);
    call("add_balloon", 0, 1, 0, 0, 9999);
    call("add_balloon", 1e30, 1, 0, 0, 0);
    call("set_velocity", 0, 1e6, 0, 0, 0, 0, 0);
    call("step", 1e9);
    call("apply_live", { control: "ribbon_length", value: NaN });
    call("apply_live", { control: "ribbon_length", value: -1 });
    call("apply_live", { control: "ribbon_length", value: 1e9 });
    call("apply_live", { control: "gravity", value: -1 });
    call("apply_live", { control: "gravity", value: Infinity });
    call("apply_live", { control: "wind", value: 1 });
    call("apply_live", "gravity");
    call("grab_ribbon", e.ribbon_count(), 1, 0, 1, 0);
    call("grab_ribbon", 0, 0, 0, 1, 0);
    call("grab_ribbon", 0, 9999, 0, 1, 0);
    call("grab_ribbon", 0, 1, NaN, 1, 0);
    const afterRefused = { count: e.body_count() as number, hash: String(e.state_hash()) };
    // A refused scene keeps the old world too; its message names the scene instead of the method.
    let scene: Call | null = null;
    try {
      e.load_scene_json('{"balloons": "many"}');
    } catch (err) {
      scene = { name: "load_scene_json", args: "", kind: (err as Error).name, message: (err as Error).message, trap: err instanceof WebAssembly.RuntimeError };
    }
    const afterScene = { count: e.body_count() as number, hash: String(e.state_hash()) };
    let stepError = "";
    try {
      e.step(10);
    } catch (err) {
      stepError = String(err);
    }
    return { errorKinds, calls, beforeWorld, n, hash, afterRefused, scene, afterScene, stepError, count: e.body_count() as number };
  });
  expect(result.errorKinds).toEqual(expect.arrayContaining(["NoWorld", "BadArgument", "OutOfRange", "Scene"]));
  expect(result.n, "the default scene has balloons").toBeGreaterThan(0);
  for (const [i, c] of result.calls.entries()) {
    const what = `${c.name}(${c.args})`;
    expect(c.trap, `${what} trapped: ${c.message}`).toBe(false);
    expect(c.kind, `${what} was refused`).not.toBeNull();
    expect(result.errorKinds, `${what} threw a known kind: ${c.kind}`).toContain(c.kind);
    const expected = i < result.beforeWorld ? ["NoWorld"] : ["BadArgument", "OutOfRange"];
    expect(expected, `${what} threw ${c.kind}: ${c.message}`).toContain(c.kind);
    expect(c.message, `${what}: the message names the method`).toMatch(new RegExp(`^${c.name}: \\S`));
  }
  expect(result.afterRefused, "no refused call changed the world").toEqual({ count: result.n, hash: result.hash });
  expect(result.scene, "a bad scene is refused").not.toBeNull();
  expect(result.scene!.trap).toBe(false);
  expect(result.scene!.kind).toBe("Scene");
  expect(result.scene!.message).toContain("balloons");
  expect(result.afterScene, "a refused scene keeps the old world").toEqual({ count: result.n, hash: result.hash });
  expect(result.stepError, "the engine still steps after every refused call").toBe("");
  expect(result.count, "stepping keeps every balloon").toBe(result.n);
});
