// Copies the repository's assets/ (balloon OBJ, per-colour MTL, example
// scenes) into public/assets/ so Vite serves and bundles them, and writes
// public/assets/manifest.json listing them (the app finds the model and
// colours there). Checks that the engine (public/wasm/up_wasm.wasm) is built.

import { cpSync, existsSync, mkdirSync, readdirSync, rmSync, statSync, writeFileSync } from "node:fs";
import { dirname, join, relative, sep } from "node:path";
import { fileURLToPath } from "node:url";

const web = join(dirname(fileURLToPath(import.meta.url)), "..");
const source = join(web, "..", "assets");
const target = join(web, "public", "assets");
const wasm = join(web, "public", "wasm", "up_wasm.wasm");

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
if (!existsSync(wasm)) {
  console.error(
    "copy-assets: public/wasm/up_wasm.wasm is missing. Build the engine first:\n" +
      "  cargo build --release -p up-wasm --target wasm32-unknown-unknown\n" +
      "  mkdir -p web/public/wasm && cp target/wasm32-unknown-unknown/release/up_wasm.wasm web/public/wasm/",
  );
  process.exit(1);
}
