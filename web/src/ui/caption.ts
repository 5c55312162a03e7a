// The loaded scene's caption: a teaching scene's `[about]` title and one
// paragraph saying what to watch, shown over the room until dismissed, and
// again whenever a scene with a caption is loaded.

import type { AboutSpec, Scene } from "../scene/sceneSchema";

/** A scene's `about`: its title and caption (the engine's `AboutSpec`). */
export type About = AboutSpec;

/** The scene's caption, or null when it has none (or an empty one). */
export function aboutOfScene(scene: Scene): About | null {
  const caption = scene.about?.caption.trim() ?? "";
  if (!caption) return null;
  return { title: scene.about?.title ?? "", caption };
}

export class SceneCaption {
  readonly element: HTMLElement;
  private readonly title: HTMLElement;
  private readonly text: HTMLElement;
  /** The caption shown, or dismissed; null when the scene has none. */
  about: About | null = null;

  constructor(parent: HTMLElement) {
    this.element = document.createElement("aside");
    this.element.id = "scene-caption";
    this.element.hidden = true;
    this.title = document.createElement("h2");
    this.text = document.createElement("p");
    const close = document.createElement("button");
    close.type = "button";
    close.className = "close";
    close.textContent = "×";
    close.title = "Hide the caption";
    close.addEventListener("click", () => (this.element.hidden = true));
    this.element.append(close, this.title, this.text);
    parent.appendChild(this.element);
  }

  /** A new scene: shows its caption, or hides the old one when it has none. */
  show(about: About | null): void {
    this.about = about;
    this.element.hidden = !about;
    if (!about) return;
    this.title.textContent = about.title;
    this.title.hidden = !about.title;
    this.text.textContent = about.caption;
  }

  get visible(): boolean {
    return !this.element.hidden;
  }
}
