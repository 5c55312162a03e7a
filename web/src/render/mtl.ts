// The few MTL fields the balloon material reads. The per-colour .mtl files of
// assets/ give each colour's diffuse (Kd) and specular (Ks, Ns) as the original did.

export interface MtlMaterial {
  name: string;
  /** Diffuse colour, linear 0–1. */
  kd: [number, number, number] | null;
  ks: [number, number, number] | null;
  /** Specular exponent, 0–1000. */
  ns: number | null;
}

export function parseMtl(text: string): MtlMaterial[] {
  const out: MtlMaterial[] = [];
  let current: MtlMaterial | null = null;
  for (const raw of text.split(/\r?\n/)) {
    const line = raw.replace(/#.*/, "").trim();
    if (!line) continue;
    const [key, ...rest] = line.split(/\s+/);
    const nums = rest.map(Number);
    if (key === "newmtl") {
      current = { name: rest.join(" "), kd: null, ks: null, ns: null };
      out.push(current);
    } else if (current && (key === "Kd" || key === "Ks") && nums.length >= 3 && nums.slice(0, 3).every(Number.isFinite)) {
      const rgb: [number, number, number] = [nums[0], nums[1], nums[2]];
      if (key === "Kd") current.kd = rgb;
      else current.ks = rgb;
    } else if (current && key === "Ns" && Number.isFinite(nums[0])) {
      current.ns = nums[0];
    }
  }
  return out;
}

/** The colour name in a per-colour MTL file name: `balloon_red.mtl` → `red`. */
export function colorNameOfMtlFile(file: string): string | null {
  const m = /(?:^|[_-])([a-z]+)\.mtl$/i.exec(file.split("/").pop() ?? "");
  return m ? m[1].toLowerCase() : null;
}
