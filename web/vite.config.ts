import { fileURLToPath } from "node:url";
import { defineConfig } from "vitest/config";
// The ".js" names keep Vite's config loader from warning about extensionless imports (they resolve to the .ts files).
import { balloonMeshPlugin } from "./scripts/balloonMeshPlugin.js";

// Cross-origin isolation: without it a page has no SharedArrayBuffer, and the
// engine's threads (Web Workers sharing the module's memory) cannot start.
// require-corp would block any cross-origin asset: the page loads none.
const ISOLATION_HEADERS = {
  "Cross-Origin-Opener-Policy": "same-origin",
  "Cross-Origin-Embedder-Policy": "require-corp",
};

// Vite's own bundles go to dist/static so they never mix with public/assets
// (the balloon OBJ/MTL and the scenes copied from ../assets); the balloon
// model baked from them goes to assets/ beside them.
export default defineConfig({
  base: "./",
  plugins: [balloonMeshPlugin(fileURLToPath(new URL("../assets", import.meta.url)))],
  build: {
    assetsDir: "static",
    target: "es2022",
    chunkSizeWarningLimit: 1500,
  },
  worker: { format: "es" },
  server: { headers: ISOLATION_HEADERS },
  preview: { port: 8080, strictPort: true, host: "0.0.0.0", headers: ISOLATION_HEADERS },
  test: {
    include: ["src/**/*.test.ts"],
    environment: "node",
  },
});
