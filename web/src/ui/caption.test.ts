import { describe, expect, it } from "vitest";
import { aboutOfScene } from "./caption";

describe("a scene's caption", () => {
  it("is the scene's about, when it has a caption", () => {
    expect(aboutOfScene({ about: { title: "Throw", caption: " A balloon thrown at a wall. " } })).toEqual({ title: "Throw", caption: "A balloon thrown at a wall." });
    expect(aboutOfScene({ about: { title: "", caption: "No title." } })).toEqual({ title: "", caption: "No title." });
  });

  it("is none without an about, or with an empty caption", () => {
    expect(aboutOfScene({ balloons: [] })).toBeNull();
    expect(aboutOfScene({ about: { title: "T", caption: "  " } })).toBeNull();
  });
});
