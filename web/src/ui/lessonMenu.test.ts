import { describe, expect, it } from "vitest";
import { aboutTitle, exampleFiles, lessonFiles, titleFromFile } from "./lessonMenu";

describe("the teaching scenes' menu", () => {
  it("lists the manifest's learn-*.toml scenes only", () => {
    const files = ["balloon.obj", "scenes/thrown.toml", "scenes/learn-throw.toml", "scenes/learn-cold-room.toml", "scenes/learn-x.json", "other/learn-y.toml"];
    expect(lessonFiles(files)).toEqual(["scenes/learn-cold-room.toml", "scenes/learn-throw.toml"]);
  });

  it("lists the other scenes apart, for those with a title to follow the lessons", () => {
    const files = ["balloon.obj", "scenes/thrown.toml", "scenes/learn-throw.toml", "scenes/birthday.toml", "scenes/x.json", "other/y.toml"];
    expect(exampleFiles(files)).toEqual(["scenes/birthday.toml", "scenes/thrown.toml"]);
  });

  it("reads the title of the [about] table, not another table's", () => {
    const toml = [
      "# a scene",
      "[room]",
      'title = "not this one"',
      "",
      "[about]",
      'title = "Terminal speed: when drag \\"balances\\" lift"  # the menu\'s name',
      'caption = "A balloon rises..."',
      "[sim]",
      "seed = 1",
    ].join("\n");
    expect(aboutTitle(toml)).toBe('Terminal speed: when drag "balances" lift');
    expect(aboutTitle("[about]\ntitle = 'Cold room'\n")).toBe("Cold room");
    expect(aboutTitle("[room]\nwidth = 2\n")).toBeNull();
    expect(aboutTitle("[about]\ncaption = 'x'\n[room]\ntitle = 'no'\n")).toBeNull();
  });

  it("names a scene without a title by its file", () => {
    expect(titleFromFile("scenes/learn-cold-room.toml")).toBe("Cold room");
  });
});
