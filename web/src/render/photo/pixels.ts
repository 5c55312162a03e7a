// Comparing pictures: how far apart two RGBA images of one size are, for the
// tests (is the photo a different picture from the live frame?) and their
// noise floor (two live frames of a paused scene).

/** Mean absolute difference of the RGB channels of two RGBA images, 0–255 (alpha left out). */
export function meanAbsDifference(a: Uint8Array | Uint8ClampedArray, b: Uint8Array | Uint8ClampedArray): number {
  if (a.length !== b.length) throw new Error(`images of different sizes: ${a.length} and ${b.length} bytes`);
  if (a.length % 4 !== 0) throw new Error(`not RGBA: ${a.length} bytes`);
  const pixels = a.length / 4;
  if (pixels === 0) return 0;
  let sum = 0;
  for (let i = 0; i < a.length; i += 4) {
    sum += Math.abs(a[i] - b[i]) + Math.abs(a[i + 1] - b[i + 1]) + Math.abs(a[i + 2] - b[i + 2]);
  }
  return sum / (pixels * 3);
}

/** Mean luminance (Rec. 709 weights) of an RGBA image, 0–255, and the share of its pixels that are pure black. */
export function brightness(px: Uint8Array | Uint8ClampedArray): { mean: number; black: number } {
  const pixels = px.length / 4;
  if (pixels === 0) return { mean: 0, black: 0 };
  let sum = 0;
  let black = 0;
  for (let i = 0; i < px.length; i += 4) {
    sum += 0.2126 * px[i] + 0.7152 * px[i + 1] + 0.0722 * px[i + 2];
    if (px[i] === 0 && px[i + 1] === 0 && px[i + 2] === 0) black++;
  }
  return { mean: sum / pixels, black: black / pixels };
}
