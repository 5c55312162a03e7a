// Bakes the balloon model (balloonMeshFile.ts) at build time: the OBJ parsed
// by three's OBJLoader, its parts merged, its vertices welded so that the
// normals come out smooth (latex has no facets), and each per-colour MTL
// file's Kd. Run by the Vite plugin (scripts/balloonMeshPlugin.ts) in Node,
// so the page never parses the text; the same code, the same three, give
// the same numbers on every build.

import * as THREE from "three";
import { OBJLoader } from "three/examples/jsm/loaders/OBJLoader.js";
import { mergeGeometries, mergeVertices } from "three/examples/jsm/utils/BufferGeometryUtils.js";
import { colorNameOfMtlFile, parseMtl } from "./mtl.js";
import type { BalloonMesh } from "./balloonMeshFile.js";

/** The welded mesh of `objText` (named `objFile` in errors) and the colours of `mtlFiles`. */
export function bakeBalloonMesh(objFile: string, objText: string, mtlFiles: { file: string; text: string }[]): BalloonMesh {
  const group = new OBJLoader().parse(objText);
  const parts: THREE.BufferGeometry[] = [];
  group.traverse((o) => {
    if ((o as THREE.Mesh).isMesh) {
      const g = (o as THREE.Mesh).geometry.clone();
      for (const name of Object.keys(g.attributes)) if (name !== "position") g.deleteAttribute(name);
      parts.push(g);
    }
  });
  if (parts.length === 0) throw new Error(`${objFile} has no faces`);
  let geometry = parts.length === 1 ? parts[0] : mergeGeometries(parts, false)!;
  // Welded vertices give smooth normals.
  geometry = mergeVertices(geometry, 1e-5);
  geometry.computeVertexNormals();
  const colors: Record<string, [number, number, number]> = {};
  for (const { file, text } of mtlFiles) {
    const name = colorNameOfMtlFile(file);
    const kd = parseMtl(text).find((m) => m.kd)?.kd;
    if (name && kd) colors[name] = kd;
  }
  const index = geometry.getIndex();
  if (!index) throw new Error(`${objFile}: welding gave no index`);
  return {
    positions: Float32Array.from(geometry.getAttribute("position").array),
    normals: Float32Array.from(geometry.getAttribute("normal").array),
    index: geometry.getAttribute("position").count <= 0x10000 ? Uint16Array.from(index.array) : Uint32Array.from(index.array),
    colors,
  };
}
