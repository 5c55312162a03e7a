// Copies the repository's assets/ (balloon OBJ, per-colour MTL, example
// scenes) into public/assets/ so Vite serves and bundles them, and writes
// public/assets/manifest.json listing them (the app finds the model and
// colours there). Checks that the engine (public/wasm/up_wasm.wasm and its
// wasm-bindgen glue up_wasm.js) is built.

import { cpSync, existsSync, mkdirSync, readdirSync, rmSync, statSync, writeFileSync } from "node:fs";
import { dirname, join, relative, sep } from "node:path";
import { fileURLToPath } from "node:url";

const web = join(dirname(fileURLToPath(import.meta.url)), "..");
const source = join(web, "..", "assets");
const target = join(web, "public", "assets");
const engine = ["up_wasm.wasm", "up_wasm.js"].map((f) => join(web, "public", "wasm", f));

if (!existsSync(source)) {
  console.error(`copy-assets: ${source} does not exist (expected the balloon model and scenes there)`);
  process.exit(1);
}
rmSync(target, { recursive: true, force: true });
mkdirSync(target, { recursive: true });
cpSync(source, target, { recursive: true });

function list(dir) {
  return readdirSync(dir).flatMap((name) => {
    const path = join(dir, name);
    return statSync(path).isDirectory() ? list(path) : [relative(target, path).split(sep).join("/")];
  });
}
const files = list(target).sort();
writeFileSync(join(target, "manifest.json"), JSON.stringify({ files }, null, 2) + "\n");
console.log(`copy-assets: ${files.length} files from ../assets to public/assets`);

if (!files.some((f) => f.endsWith(".obj"))) {
  console.error("copy-assets: no .obj balloon model in ../assets");
  process.exit(1);
}
const missing = engine.filter((f) => !existsSync(f));
if (missing.length > 0) {
  console.error(
    `copy-assets: ${missing.map((f) => relative(web, f)).join(" and ")} missing. Build the engine first ` +
      "(cargo build of up-wasm, then wasm-bindgen):\n  make web/public/wasm/up_wasm.wasm",
  );
  process.exit(1);
}
