// Messages in the page: a dismissible banner for recoverable errors (a
// malformed shared link, a scene the engine refused) and a full-page notice
// for fatal ones (no WebGL, the engine failed to load).

export class Messages {
  /** Every message shown, for the end-to-end tests. */
  readonly shown: string[] = [];

  constructor(
    private readonly banner: HTMLElement,
    private readonly fatalBox: HTMLElement,
  ) {
    banner.addEventListener("click", (e) => {
      if ((e.target as HTMLElement).classList.contains("close")) this.clear();
    });
  }

  error(text: string): void {
    this.shown.push(text);
    this.banner.innerHTML = "";
    const span = document.createElement("span");
    span.textContent = text;
    const close = document.createElement("button");
    close.className = "close";
    close.textContent = "×";
    close.title = "Dismiss";
    this.banner.append(span, close);
    this.banner.hidden = false;
  }

  clear(): void {
    this.banner.hidden = true;
  }

  fatal(title: string, detail: string): void {
    this.shown.push(`${title}: ${detail}`);
    this.fatalBox.innerHTML = "";
    const h = document.createElement("h2");
    h.textContent = title;
    const p = document.createElement("p");
    p.textContent = detail;
    this.fatalBox.append(h, p);
    this.fatalBox.hidden = false;
  }
}
