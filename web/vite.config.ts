import { defineConfig } from "vitest/config";

// Vite's own bundles go to dist/static so they never mix with public/assets
// (the balloon OBJ/MTL and the scenes copied from ../assets).
export default defineConfig({
  base: "./",
  build: {
    assetsDir: "static",
    target: "es2022",
    chunkSizeWarningLimit: 1500,
  },
  worker: { format: "es" },
  preview: { port: 8080, strictPort: true, host: "0.0.0.0" },
  test: {
    include: ["src/**/*.test.ts"],
    environment: "node",
  },
});
