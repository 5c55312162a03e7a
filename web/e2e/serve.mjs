// The built app (dist/) for the screenshot and the measurement scripts,
// served by `vite preview` as the Playwright tests' web server does: with
// vite.config.ts's cross-origin isolation headers, or, for the tests of a
// page that is not isolated, without them.

import { dirname, join } from "node:path";
import { fileURLToPath } from "node:url";
import { preview } from "vite";

/**
 * Serves dist/ on 127.0.0.1 and a free port; resolves to { url, close }.
 * `isolated: false` leaves vite.config.ts out, and with it the COOP/COEP headers.
 */
export async function serveDist({ isolated = true } = {}) {
  const root = join(dirname(fileURLToPath(import.meta.url)), "..");
  const server = await preview({
    root,
    ...(isolated ? {} : { configFile: false }),
    logLevel: "warn",
    preview: { host: "127.0.0.1", port: 0, strictPort: true, open: false },
  });
  return { url: server.resolvedUrls.local[0], close: () => server.close() };
}
