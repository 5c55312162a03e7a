// node --test web/determinism/bodyHashes.test.mjs (make test-determinism runs it).

import assert from "node:assert/strict";
import { test } from "node:test";
import { describeParting, fieldsOf, firstParting } from "./bodyHashes.mjs";

const header =
  "# up body hashes: step state_hash, then per body index.generation/user_data:position,rotation,linear_velocity,angular_velocity,awake,ribbon,gas";
const fields = fieldsOf(header);
const line = "12 00ff00ff00ff00ff 0.0/0:aa,bb,cc,dd,ee,ff,11 1.0/1:a1,b1,c1,d1,e1,f1,12 2.0/2:a2,b2,c2,d2,e2,f2,13";

test("the header names the seven fields", () => {
  assert.deepEqual(fields, ["position", "rotation", "linear_velocity", "angular_velocity", "awake", "ribbon", "gas"]);
  assert.throws(() => fieldsOf("step,up"));
});

test("equal lines do not part", () => {
  assert.equal(firstParting(line, line, fields), null);
});

test("a body's field that differs is named with its step and body", () => {
  const found = line.replace("1.0/1:a1,b1,c1,d1", "1.0/1:a1,b1,c1,d9").replace("00ff00ff00ff00ff", "00ff00ff00ff0000");
  const parting = firstParting(line, found, fields);
  assert.deepEqual(parting, { step: "12", body: "1.0/1", field: "angular_velocity" });
  assert.match(describeParting(parting), /step 12, body 1\.0 .*user data 1\).*angular_velocity/);
});

test("the first body in order is named when several differ", () => {
  const found = line.replace(",f2,", ",f0,").replace("aa,", "a0,");
  assert.deepEqual(firstParting(line, found, fields), { step: "12", body: "0.0/0", field: "position" });
});

test("a missing body, and a state hash alone", () => {
  const shorter = line.split(" ").slice(0, 4).join(" ");
  assert.deepEqual(firstParting(line, shorter, fields), { step: "12", body: "2.0/2", field: "bodies" });
  const hashOnly = line.replace("00ff00ff00ff00ff", "1111111111111111");
  const parting = firstParting(line, hashOnly, fields);
  assert.deepEqual(parting, { step: "12", body: null, field: "rest" });
  assert.match(describeParting(parting), /step 12: the state hash/);
});
