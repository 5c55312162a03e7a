// The balloon model as the page loads it: assets/balloon.obj welded into an
// indexed mesh with smooth normals, and each colour of the per-colour MTL
// files, baked at build time (balloonMeshBake.ts, run by the Vite plugin in
// scripts/balloonMeshPlugin.ts) into one small binary file, so that the page
// fetches one file (preloaded by index.html from the first byte) and reads
// it into typed arrays without parsing text.
//
// Layout, little-endian, every part 4-byte aligned:
//   "UPBM" · u32 version · u32 header bytes (JSON, padded with spaces) · JSON header
//   · positions f32[3·vertices] · normals f32[3·vertices] · index u16 or u32[indices]

/** The baked file's name in the assets folder (beside balloon.obj). */
export const BALLOON_MESH_FILE = "balloon-mesh.bin";

const MAGIC = 0x4d425055; // "UPBM" read as a little-endian u32
const VERSION = 1;
const PREAMBLE_BYTES = 12;

/** The welded balloon and its colours. */
export interface BalloonMesh {
  /** xyz per vertex, m. */
  positions: Float32Array;
  /** Unit normals, xyz per vertex. */
  normals: Float32Array;
  /** Three vertex indices per triangle. */
  index: Uint16Array | Uint32Array;
  /** Linear RGB of each colour name found in the MTL files (their Kd). */
  colors: Record<string, [number, number, number]>;
}

interface Header {
  vertices: number;
  indices: number;
  indexBytes: 2 | 4;
  colors: Record<string, [number, number, number]>;
}

const pad4 = (n: number) => (n + 3) & ~3;

/** The file's bytes for `mesh`. */
export function encodeBalloonMesh(mesh: BalloonMesh): Uint8Array {
  const vertices = mesh.positions.length / 3;
  if (mesh.normals.length !== mesh.positions.length) throw new Error("balloon mesh: as many normals as positions expected");
  const indexBytes = vertices <= 0x10000 ? 2 : 4;
  const header: Header = { vertices, indices: mesh.index.length, indexBytes, colors: mesh.colors };
  const json = new TextEncoder().encode(JSON.stringify(header));
  const headerBytes = pad4(json.length);
  const arrays = PREAMBLE_BYTES + headerBytes;
  const total = arrays + 2 * 12 * vertices + pad4(indexBytes * mesh.index.length);
  const bytes = new Uint8Array(total);
  const view = new DataView(bytes.buffer);
  view.setUint32(0, MAGIC, true);
  view.setUint32(4, VERSION, true);
  view.setUint32(8, headerBytes, true);
  bytes.fill(0x20, PREAMBLE_BYTES, arrays);
  bytes.set(json, PREAMBLE_BYTES);
  let at = arrays;
  const put = (values: ArrayLike<number>, width: 2 | 4, float: boolean) => {
    for (let i = 0; i < values.length; i++, at += width) {
      if (float) view.setFloat32(at, values[i], true);
      else if (width === 2) view.setUint16(at, values[i], true);
      else view.setUint32(at, values[i], true);
    }
  };
  put(mesh.positions, 4, true);
  put(mesh.normals, 4, true);
  put(mesh.index, indexBytes, false);
  return bytes;
}

/** Reads the file's bytes; throws, saying what is wrong, on anything else. */
export function decodeBalloonMesh(buffer: ArrayBuffer): BalloonMesh {
  const fail = (why: string): never => {
    throw new Error(`${BALLOON_MESH_FILE}: ${why}`);
  };
  if (buffer.byteLength < PREAMBLE_BYTES) fail("too short");
  const view = new DataView(buffer);
  if (view.getUint32(0, true) !== MAGIC) fail("not a baked balloon mesh");
  if (view.getUint32(4, true) !== VERSION) fail(`version ${view.getUint32(4, true)}, expected ${VERSION}`);
  const headerBytes = view.getUint32(8, true);
  const arrays = PREAMBLE_BYTES + headerBytes;
  if (headerBytes % 4 !== 0 || arrays > buffer.byteLength) fail("bad header length");
  const header = JSON.parse(new TextDecoder().decode(new Uint8Array(buffer, PREAMBLE_BYTES, headerBytes))) as Header;
  const { vertices, indices, indexBytes } = header;
  if (arrays + 24 * vertices + pad4(indexBytes * indices) !== buffer.byteLength) fail("length does not match its header");
  // Typed arrays read the platform's byte order: every browser's is little-endian, as the file's.
  const positions = new Float32Array(buffer, arrays, 3 * vertices);
  const normals = new Float32Array(buffer, arrays + 12 * vertices, 3 * vertices);
  const indexAt = arrays + 24 * vertices;
  const index = indexBytes === 2 ? new Uint16Array(buffer, indexAt, indices) : new Uint32Array(buffer, indexAt, indices);
  return { positions, normals, index, colors: header.colors };
}
