// The Khronos glTF validator (npm `gltf-validator`) ships no types: what the tests use of it.
declare module "gltf-validator" {
  export interface ValidationReport {
    issues: { numErrors: number; numWarnings: number; numInfos: number; numHints: number; messages: { code: string; message: string; severity: number; pointer?: string }[] };
    info?: { animationCount?: number; materialCount?: number; totalVertexCount?: number; extensionsUsed?: string[] };
  }
  export function validateBytes(data: Uint8Array, options?: { maxIssues?: number; ignoredIssues?: string[]; format?: "glb" | "gltf" }): Promise<ValidationReport>;
}
