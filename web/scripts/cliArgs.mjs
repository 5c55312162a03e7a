// What the Node tools' command lines share (web/bench/bench.mjs, web/e2e/measure.mjs).

/** `value` as an integer in [min, max], else an error naming the flag, the range and what was given. */
export function intArg(name, value, min, max) {
  const n = Number(value);
  if (!Number.isInteger(n) || n < min || n > max) {
    throw new Error(`${name}: expected an integer from ${min} to ${max}, found ${JSON.stringify(value)}`);
  }
  return n;
}
