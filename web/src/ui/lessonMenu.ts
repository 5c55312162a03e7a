// The teaching scenes (assets/scenes/learn-*.toml), then the other scenes
// that carry an `[about] title` (the examples that say what they show), and
// the panel's "Scenes" folder: a menu of them by that title, and the "forces
// on all" switch. A chosen scene is built by the engine from its TOML, as the CLI
// builds it; its caption comes back in the scene the engine wrote (caption.ts).

import type GUI from "lil-gui";

/** A teaching scene in the asset manifest. */
export const LESSON_FILE = /^scenes\/learn-[a-z0-9-]+\.toml$/;

export interface Lesson {
  /** Path in the asset folder ("scenes/learn-throw.toml"). */
  file: string;
  title: string;
  /** The scene file's text, handed to the engine as it is. */
  toml: string;
}

/** Any scene in the asset manifest. */
const SCENE_FILE = /^scenes\/[a-z0-9-]+\.toml$/;

/** The manifest's teaching scenes, in file order. */
export function lessonFiles(files: readonly string[]): string[] {
  return files.filter((f) => LESSON_FILE.test(f)).sort();
}

/** The manifest's other scenes, in file order: listed only where they have a title. */
export function exampleFiles(files: readonly string[]): string[] {
  return files.filter((f) => SCENE_FILE.test(f) && !LESSON_FILE.test(f)).sort();
}

/**
 * The `title` of a scene file's `[about]` table, or null when it has none.
 * Reads only that key (a basic or literal one-line string): the engine is the
 * scene's reader, this only names the menu's entries before one is loaded.
 */
export function aboutTitle(toml: string): string | null {
  let inAbout = false;
  for (const raw of toml.split(/\r?\n/)) {
    const line = raw.trim();
    if (line.startsWith("[")) {
      inAbout = /^\[\s*about\s*\]\s*(#.*)?$/.test(line);
      continue;
    }
    if (!inAbout) continue;
    const m = /^title\s*=\s*("(?:[^"\\]|\\.)*"|'[^']*')\s*(#.*)?$/.exec(line);
    if (!m) continue;
    const value = m[1];
    if (value.startsWith("'")) return value.slice(1, -1);
    try {
      return JSON.parse(value) as string;
    } catch {
      return value.slice(1, -1);
    }
  }
  return null;
}

/** A title from the file's name when the scene has none: "learn-cold-room.toml" → "Cold room". */
export function titleFromFile(file: string): string {
  const stem = file.replace(/^.*\//, "").replace(/^learn-/, "").replace(/\.toml$/, "").replace(/-/g, " ");
  return stem.charAt(0).toUpperCase() + stem.slice(1);
}

/** Fetches the manifest's teaching scenes, then its titled other scenes, under `base` (the assets' URL, ending in "/"). */
export async function loadLessons(base: string): Promise<Lesson[]> {
  const response = await fetch(`${base}manifest.json`);
  if (!response.ok) throw new Error(`cannot load ${base}manifest.json: HTTP ${response.status}`);
  const { files } = (await response.json()) as { files: string[] };
  const read = async (file: string) => {
    const r = await fetch(base + file);
    if (!r.ok) throw new Error(`cannot load ${file}: HTTP ${r.status}`);
    const toml = await r.text();
    return { file, title: aboutTitle(toml), toml };
  };
  const lessons = await Promise.all(lessonFiles(files).map(read));
  const examples = await Promise.all(exampleFiles(files).map(read));
  return [
    ...lessons.map((l) => ({ ...l, title: l.title ?? titleFromFile(l.file) })),
    ...examples.flatMap((e) => (e.title === null ? [] : [{ ...e, title: e.title }])),
  ];
}

export interface LessonActions {
  load(lesson: Lesson): void;
  forcesOnAll(on: boolean): void;
}

/** The panel's "Scenes" folder. */
export class LessonMenu {
  readonly folder: GUI;
  private readonly view = { lesson: "", forcesOnAll: false };

  constructor(gui: GUI, lessons: Lesson[], actions: LessonActions) {
    this.folder = gui.addFolder("Scenes");
    // First in the panel: the way in for a learner.
    gui.$children.prepend(this.folder.domElement);
    const options: Record<string, string> = { "choose a scene…": "" };
    for (const l of lessons) options[l.title] = l.file;
    const menu = this.folder.add(this.view, "lesson", options).name("scene");
    menu.domElement.dataset.key = "lesson";
    menu.onChange((file: string) => {
      const lesson = lessons.find((l) => l.file === file);
      if (lesson) actions.load(lesson);
    });
    const all = this.folder.add(this.view, "forcesOnAll").name("forces on all");
    all.domElement.dataset.key = "forcesOnAll";
    all.onChange((on: boolean) => actions.forcesOnAll(on));
  }
}
