// The Vite plugin that bakes the balloon model (src/render/balloonMeshFile.ts)
// from the repository's assets/: balloon.obj and the per-colour MTL files.
// A build writes it to dist/assets/ beside the copied OBJ; the dev server
// bakes it afresh for each request; both pages' index.html preload it from
// their first byte, so the model is in while the bundle still loads.

import { readFileSync, readdirSync } from "node:fs";
import { join } from "node:path";
import type { Plugin } from "vite";
import { bakeBalloonMesh } from "../src/render/balloonMeshBake.js";
import { BALLOON_MESH_FILE, encodeBalloonMesh } from "../src/render/balloonMeshFile.js";

/** The baked file's bytes from the model and colours in `assetsDir`. */
export function bakeBalloonMeshFile(assetsDir: string): Uint8Array {
  const files = readdirSync(assetsDir).sort();
  const obj = files.find((f) => f.toLowerCase() === "balloon.obj") ?? files.find((f) => f.endsWith(".obj"));
  if (!obj) throw new Error(`the balloon model (${join(assetsDir, "balloon.obj")}) is missing`);
  const mtl = files.filter((f) => f.endsWith(".mtl")).map((file) => ({ file, text: readFileSync(join(assetsDir, file), "utf8") }));
  return encodeBalloonMesh(bakeBalloonMesh(obj, readFileSync(join(assetsDir, obj), "utf8"), mtl));
}

/** Bakes the balloon model of `assetsDir` into assets/ of the build and the dev server. */
export function balloonMeshPlugin(assetsDir: string): Plugin {
  const path = `assets/${BALLOON_MESH_FILE}`;
  return {
    name: "up-balloon-mesh",
    configureServer(server) {
      server.middlewares.use(`/${path}`, (_request, response) => {
        response.setHeader("Content-Type", "application/octet-stream");
        response.end(Buffer.from(bakeBalloonMeshFile(assetsDir)));
      });
    },
    generateBundle() {
      this.emitFile({ type: "asset", fileName: path, source: bakeBalloonMeshFile(assetsDir) });
    },
    // The same request as the page's fetch (cors, same-origin credentials), so that the fetch takes the preload.
    transformIndexHtml() {
      return [{ tag: "link", attrs: { rel: "preload", href: path, as: "fetch", crossorigin: "anonymous" }, injectTo: "head-prepend" }];
    },
  };
}
