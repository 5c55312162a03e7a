// The scene shared as a link: `#scene=<base64url of the scene's JSON>`.
// Decoding checks the link's own layers (length, base64url, UTF-8, a JSON
// object) and says which one is wrong; whether the scene itself is valid is
// the engine's to say when it loads it, in its own words, and the app then
// falls back to the default scene.

/** The URL hash key that carries the scene. */
export const SCENE_PARAM = "scene";

/** Links longer than this are refused before decoding (characters). */
export const MAX_LINK_CHARS = 200_000;

export type DecodeResult =
  | { ok: true; scene: Record<string, unknown>; json: string }
  | { ok: false; error: string };

/** UTF-8 bytes to unpadded base64url. */
export function toBase64Url(bytes: Uint8Array): string {
  let binary = "";
  for (let i = 0; i < bytes.length; i += 0x8000) {
    binary += String.fromCharCode(...bytes.subarray(i, i + 0x8000));
  }
  return btoa(binary).replace(/\+/g, "-").replace(/\//g, "_").replace(/=+$/, "");
}

/** Unpadded (or padded) base64url to bytes; `null` when it is not base64url. */
export function fromBase64Url(text: string): Uint8Array | null {
  if (!/^[A-Za-z0-9_-]*={0,2}$/.test(text)) return null;
  const plain = text.replace(/=+$/, "");
  if (plain.length % 4 === 1) return null;
  const base64 = plain.replace(/-/g, "+").replace(/_/g, "/") + "=".repeat((4 - (plain.length % 4)) % 4);
  try {
    const binary = atob(base64);
    const bytes = new Uint8Array(binary.length);
    for (let i = 0; i < binary.length; i++) bytes[i] = binary.charCodeAt(i);
    return bytes;
  } catch {
    return null;
  }
}

/** The hash fragment (`#scene=...`) for a scene given as its JSON text. */
export function encodeSceneHash(json: string): string {
  // Re-serialise compactly: links stay short and whitespace does not matter.
  const compact = JSON.stringify(JSON.parse(json));
  return `#${SCENE_PARAM}=${toBase64Url(new TextEncoder().encode(compact))}`;
}

/** The `scene` value in a hash such as `#scene=...&x=1`, or `null` when absent. */
export function sceneParam(hash: string): string | null {
  const body = hash.startsWith("#") ? hash.slice(1) : hash;
  for (const part of body.split("&")) {
    const eq = part.indexOf("=");
    const key = eq < 0 ? part : part.slice(0, eq);
    if (key === SCENE_PARAM) return eq < 0 ? "" : part.slice(eq + 1);
  }
  return null;
}

/** Decodes the scene of a shared link (the `scene` parameter's value) into its JSON text. */
export function decodeSceneParam(value: string): DecodeResult {
  const where = "shared link";
  if (value.length === 0) return { ok: false, error: `${where}: the scene parameter is empty` };
  if (value.length > MAX_LINK_CHARS) {
    return { ok: false, error: `${where}: the scene is ${value.length} characters long, expected at most ${MAX_LINK_CHARS}` };
  }
  let text: string;
  try {
    text = decodeURIComponent(value);
  } catch {
    return { ok: false, error: `${where}: the scene is not base64url text (bad % escape)` };
  }
  const bytes = fromBase64Url(text);
  if (!bytes) return { ok: false, error: `${where}: the scene is not base64url text` };
  let json: string;
  try {
    json = new TextDecoder("utf-8", { fatal: true }).decode(bytes);
  } catch {
    return { ok: false, error: `${where}: the scene is not UTF-8 text` };
  }
  let scene: unknown;
  try {
    scene = JSON.parse(json);
  } catch (e) {
    return { ok: false, error: `${where}: the scene is not valid JSON (${(e as Error).message})` };
  }
  if (typeof scene !== "object" || scene === null || Array.isArray(scene)) {
    return { ok: false, error: `${where}: the scene is not a JSON object (with room, balloons, air and sim)` };
  }
  return { ok: true, scene: scene as Record<string, unknown>, json };
}
