// The surfaces balloons are drawn with, one MeshPhysicalMaterial per finish
// (a scene group's `finish`: latex, pearl or foil), starting from the physics
// reference's "Looks" and judged by eye against photographs:
//
// - latex: a glossy clearcoat over a softer body (roughness 0.35, clearcoat 1
//   at 0.1), a little transmission (0.25 through ≈ 1 cm) so a balloon glows
//   in its own colour with the light behind it, and sheen, the velvet of
//   oxidised latex, that grows as the balloons age (`setAge`). The neck's
//   pleats and the knot's crinkles are a normal map generated at start,
//   drawn on a uv the page gives the latex mesh (`addLatexUv`: around the
//   axis and down from the top);
// - pearl: the same latex with a mother-of-pearl shimmer (iridescence, a thin
//   film of 380 nm);
// - foil: metal (metalness 1, roughness 0.12) with a normal map of fine
//   creases: a chrome latex balloon, or (foilBalloons.ts) a foil one.

import * as THREE from "three";
import type { Finish } from "../sim/engine";
import { normalMapFromHeight, seededRandom } from "./normalMap";

/** Every finish, in the panel's order. */
export const FINISHES: readonly Finish[] = ["latex", "pearl", "foil"];

/** Texels across the generated normal maps. */
const NORMAL_TEXELS = 256;
/** Pleats around the neck, where the tied latex gathers. */
const NECK_PLEATS = 14;
/** How far down the balloon (uv v, from the top) the neck's pleats start to show. */
const NECK_PLEATS_FROM = 0.72;
/** Sheen of fresh and of fully aged latex: the velvet grows as the gas goes. */
export const SHEEN_FRESH = 0.08;
export const SHEEN_AGED = 0.7;

/**
 * Height of the latex surface at (u around, v down from the top): smooth over
 * the body; pleats gathering into the neck, deepening toward it; crinkles on
 * the knot at the very bottom.
 */
export function latexHeight(u: number, v: number): number {
  const toNeck = Math.min(1, Math.max(0, (v - NECK_PLEATS_FROM) / (1 - NECK_PLEATS_FROM)));
  const pleat = Math.abs(Math.sin(Math.PI * NECK_PLEATS * u + 2.5 * Math.sin(2 * Math.PI * u) * toNeck));
  const knot = v > 0.95 ? 0.5 + 0.5 * Math.sin(37 * 2 * Math.PI * u) * Math.sin(60 * v) : 0;
  return toNeck * toNeck * pleat * 0.6 + knot * 0.2;
}

/** Fine creases all over, as metallised film (or a metal coat on latex) takes them. */
function creaseHeight(rnd: () => number): (u: number, v: number) => number {
  const waves = Array.from({ length: 9 }, () => ({
    // Whole turns around u, so the seam stays seamless.
    ku: Math.round(3 + rnd() * 20),
    kv: 4 + rnd() * 30,
    phase: rnd() * Math.PI * 2,
    a: 0.3 + rnd() * 0.7,
  }));
  return (u, v) => {
    let h = 0;
    for (const w of waves) h += w.a * Math.abs(Math.sin(2 * Math.PI * w.ku * u + w.kv * v + w.phase));
    return h / waves.length;
  };
}

/**
 * Gives the latex balloon geometry a uv: u around the axis (Y), v from the
 * top down, so the normal maps land on the neck and the knot whatever the
 * mesh's resolution. The uv seam (u = 0 and 1 at −X) shares its vertices, so
 * one triangle row there interpolates across the map: invisible at these
 * creases' size.
 */
export function addLatexUv(geometry: THREE.BufferGeometry): void {
  const p = geometry.getAttribute("position");
  let top = -Infinity;
  let bottom = Infinity;
  for (let i = 0; i < p.count; i++) {
    top = Math.max(top, p.getY(i));
    bottom = Math.min(bottom, p.getY(i));
  }
  const uv = new Float32Array(p.count * 2);
  for (let i = 0; i < p.count; i++) {
    uv[2 * i] = Math.atan2(p.getZ(i), p.getX(i)) / (2 * Math.PI) + 0.5;
    uv[2 * i + 1] = (top - p.getY(i)) / Math.max(1e-9, top - bottom);
  }
  geometry.setAttribute("uv", new THREE.BufferAttribute(uv, 2));
}

/** The latex body every latex finish shares. */
function latexParameters(): THREE.MeshPhysicalMaterialParameters {
  return {
    color: 0xffffff,
    roughness: 0.35,
    metalness: 0,
    clearcoat: 1,
    clearcoatRoughness: 0.1,
    // Light through the latex: the balloon glows in its own colour from behind.
    transmission: 0.25,
    thickness: 0.01,
    ior: 1.52,
    sheen: SHEEN_FRESH,
    sheenRoughness: 0.6,
    sheenColor: new THREE.Color(0xffffff),
    specularIntensity: 0.6,
    envMapIntensity: 0.9,
  };
}

/** One material per finish, made on first use and shared by every mesh that draws it. */
export class FinishMaterials {
  private readonly made = new Map<Finish, THREE.MeshPhysicalMaterial>();
  private latexNormals: THREE.DataTexture | null = null;
  private creaseNormals: THREE.DataTexture | null = null;
  private age = 0;

  /** `prepare` is applied to each material made (the squash's shader patch). */
  constructor(private readonly prepare: (m: THREE.MeshPhysicalMaterial) => void = () => {}) {}

  get(finish: Finish): THREE.MeshPhysicalMaterial {
    let m = this.made.get(finish);
    if (!m) {
      m = this.make(finish);
      m.name = `balloon-${finish}`;
      this.prepare(m);
      this.made.set(finish, m);
      this.applyAge(m);
    }
    return m;
  }

  private make(finish: Finish): THREE.MeshPhysicalMaterial {
    if (finish === "foil") {
      this.creaseNormals ??= normalMapFromHeight(creaseHeight(seededRandom(11)), 3, NORMAL_TEXELS);
      return new THREE.MeshPhysicalMaterial({
        color: 0xffffff,
        metalness: 1,
        roughness: 0.12,
        normalMap: this.creaseNormals,
        normalScale: new THREE.Vector2(0.5, 0.5),
        envMapIntensity: 1,
      });
    }
    this.latexNormals ??= normalMapFromHeight(latexHeight, 6, NORMAL_TEXELS);
    const m = new THREE.MeshPhysicalMaterial({ ...latexParameters(), normalMap: this.latexNormals, normalScale: new THREE.Vector2(0.8, 0.8) });
    if (finish === "pearl") {
      m.iridescence = 1;
      m.iridescenceIOR = 1.3;
      // Without a thickness map the film is its maximum throughout: the shimmer shifts with the angle alone.
      m.iridescenceThicknessMinimum = 250;
      m.iridescenceThicknessMaximum = 380;
      m.sheen = 0;
      m.transmission = 0.15;
    }
    return m;
  }

  /**
   * How aged the latex looks, 0 (fresh) to 1 (its float spent): the sheen,
   * oxidised latex's velvet, follows it. Pearl keeps its shimmer instead.
   */
  setAge(age: number): void {
    const a = Math.min(1, Math.max(0, age));
    if (Math.abs(a - this.age) < 1e-3) return;
    this.age = a;
    for (const m of this.made.values()) this.applyAge(m);
  }

  private applyAge(m: THREE.MeshPhysicalMaterial): void {
    if (m.metalness > 0 || m.iridescence > 0) return;
    m.sheen = SHEEN_FRESH + (SHEEN_AGED - SHEEN_FRESH) * this.age;
    // The oxidised skin dulls the gloss a little too.
    m.clearcoat = 1 - 0.5 * this.age;
    m.roughness = 0.35 + 0.15 * this.age;
  }

  /** The finish `m` draws, or null for another material. */
  finishOf(m: THREE.Material): Finish | null {
    for (const [f, made] of this.made) if (made === m) return f;
    return null;
  }

  dispose(): void {
    for (const m of this.made.values()) m.dispose();
    this.made.clear();
    this.latexNormals?.dispose();
    this.creaseNormals?.dispose();
  }
}
