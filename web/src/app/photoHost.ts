// Photo mode's view of the app: the stage it draws on, the live scene it
// bakes, the room its lamp is fitted to, the ribbons' points now, the pause,
// and where its state is shown (the HUD's line, the panel's buttons).

import { writeRibbonTexels } from "../render/ribbons";
import { RIBBON_POINT_STRIDE } from "../sim/frameLayout";
import type { App } from "./app";
import type { PhotoHost } from "../render/photo/photoMode";
import type { RibbonSource } from "../render/photo/bake";

export function photoHost(app: App): PhotoHost {
  const { renderer, scene, camera } = app.stage;
  return {
    renderer,
    scene,
    camera,
    exclude: [app.world.debug.group],
    room() {
      // The room's bounds from its own triangles (centred on the origin, floor at 0).
      const v = app.info?.room.vertices ?? [];
      let halfWidth = 0;
      let halfDepth = 0;
      let top = 0;
      for (let i = 0; i + 2 < v.length; i += 3) {
        halfWidth = Math.max(halfWidth, Math.abs(v[i]));
        top = Math.max(top, v[i + 1]);
        halfDepth = Math.max(halfDepth, Math.abs(v[i + 2]));
      }
      return { halfWidth: halfWidth || 3, halfDepth: halfDepth || 3, top: top || 4.5 };
    },
    ribbons(): RibbonSource | null {
      const ribbons = app.world.ribbons;
      const { bridge } = app;
      const n = bridge.ribbons.bodies.length;
      const points = bridge.ribbons.offsets[n] ?? 0;
      if (!ribbons || !app.info || n === 0 || bridge.ribbonsCurr.length < points * RIBBON_POINT_STRIDE) return null;
      // The points as the live view drew them last: blended between the frame's two steps.
      const texels = new Float32Array(points * 4);
      writeRibbonTexels(texels, bridge.ribbonsPrev, bridge.ribbonsCurr, points, bridge.alpha(performance.timeOrigin + performance.now()));
      return { mesh: ribbons.mesh, texels, halfWidth: app.info.constants.ribbon_width_m / 2 };
    },
    paused: () => app.bridge.paused,
    setPaused(paused) {
      app.bridge.setPaused(paused);
      app.panel?.setPaused(paused);
      app.toolbar.setPaused(paused);
    },
    error: (message) => app.messages.error(message),
    changed(state) {
      app.hud.setPhoto(state.active ? state.samples : null);
      app.panel?.setPhoto(state.active);
      app.toolbar.setPhoto(state.active);
    },
  };
}
