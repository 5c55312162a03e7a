// The built engine (public/wasm/up_wasm.js and up_wasm.wasm) loaded in Node,
// for the tests that hold the page to the module's contract.

import { existsSync, readFileSync } from "node:fs";
import { Engine, type GlueModule } from "./engine";

const dir = new URL("../../public/wasm/", import.meta.url);

/** A fresh engine from the built module; throws, saying how to build it, when it is missing. */
export async function loadBuiltEngine(): Promise<Engine> {
  const wasm = new URL("up_wasm.wasm", dir);
  const glue = new URL("up_wasm.js", dir);
  for (const file of [wasm, glue]) {
    if (!existsSync(file)) throw new Error(`${file.pathname} is missing: build the engine first (make web/public/wasm/up_wasm.wasm)`);
  }
  const module = (await import(/* @vite-ignore */ glue.href)) as GlueModule;
  return Engine.load(module, readFileSync(wasm));
}
