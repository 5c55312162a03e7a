// The page's address as the scene's share link: the scene a link opened the
// page with, the address kept in step with the scene shown, and the copy of
// that address for the panel's share button.

import { decodeSceneParam, encodeSceneHash, sceneParam } from "../scene/sceneLink";
import type { Messages } from "../ui/messages";

export class ShareLink {
  /** The linked scene went to the engine and its answer (ready or error) has not come yet. */
  pending = false;

  constructor(private readonly messages: Messages) {}

  /**
   * The scene JSON the page was opened with, or null for the default scene.
   * A malformed link is reported, dropped from the address, and gives null.
   */
  takeInitial(): string | null {
    const param = sceneParam(location.hash);
    if (param === null) return null;
    const decoded = decodeSceneParam(param);
    if (decoded.ok) {
      this.pending = true;
      return decoded.json;
    }
    this.messages.error(`${decoded.error}. Showing the default scene instead.`);
    history.replaceState(null, "", location.pathname + location.search);
    return null;
  }

  /** Writes the scene into the address (null: the default scene, no hash); no history entry. */
  set(json: string | null): void {
    history.replaceState(null, "", location.pathname + location.search + (json ? encodeSceneHash(json) : ""));
  }

  /** Puts `json` in the address and copies the address; `copied` runs once it is on the clipboard. */
  share(json: string, copied: () => void): void {
    this.set(json);
    const url = location.href;
    const ask = () => window.prompt("Copy this link to share the scene:", url);
    // Without the clipboard API (plain http), the user copies it from a prompt.
    navigator.clipboard?.writeText(url).then(copied, ask) ?? ask();
  }
}
