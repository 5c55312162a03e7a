// Where two runs part, from their body hash lines: the lines
// `up run --body-hashes FILE` writes (after a header, one a step) and the
// wasm engine's `body_hash_line()` gives, both from
// up_physics::divergence::body_hash_line:
//
//   <step> <state hash> <index>.<generation>/<user data>:<hash>,<hash>,... ...
//
// one token a body in dense order, its field hashes in the order the header
// names them.

/** The field names of a body hash file's header line. */
export function fieldsOf(header) {
  const match = /:([a-z_,]+)$/.exec(header ?? "");
  if (!header?.startsWith("# up body hashes") || !match) {
    throw new Error(`not a body hash header: ${JSON.stringify(header)}`);
  }
  return match[1].split(",");
}

/**
 * The first difference between two lines of the same step: null when equal;
 * else { step, body, field } where body is "index.generation/user data" (null
 * when no one body differs) and field a name of `fields`, "bodies" (the
 * bodies themselves differ) or "rest" (only the state hash: the clock, the
 * air or a sleep timer).
 */
export function firstParting(expected, found, fields) {
  if (expected === found) return null;
  const a = expected.split(" ");
  const b = found.split(" ");
  const step = a[0];
  if (a[0] !== b[0]) return { step, body: null, field: `step (one line is of step ${b[0]})` };
  for (let k = 2; k < Math.max(a.length, b.length); k++) {
    if (a[k] === b[k]) continue;
    const [whoA, hashesA = ""] = (a[k] ?? "").split(":");
    const [whoB, hashesB = ""] = (b[k] ?? "").split(":");
    if (whoA !== whoB) return { step, body: whoA ?? whoB, field: "bodies" };
    const ha = hashesA.split(",");
    const hb = hashesB.split(",");
    const i = ha.findIndex((h, j) => h !== hb[j]);
    return { step, body: whoA, field: fields[i] ?? `field ${i}` };
  }
  return { step, body: null, field: "rest" };
}

/** A parting in words. */
export function describeParting({ step, body, field }) {
  if (body === null) {
    const what = field === "rest" ? "the state hash, in no body's fields (the clock, the air or a sleep timer)" : field;
    return `first parted at step ${step}: ${what}`;
  }
  const [index, userData] = body.split("/");
  return `first parted at step ${step}, body ${index} (index.generation; user data ${userData}): ${field} differs`;
}
