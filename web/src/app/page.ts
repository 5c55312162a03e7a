// The page's fixed elements (index.html), found once.

export interface PageElements {
  /** Holds the canvas. */
  app: HTMLElement;
  hud: HTMLElement;
  /** The banner for recoverable errors. */
  message: HTMLElement;
  /** The full-page notice for fatal errors. */
  fatal: HTMLElement;
  loading: HTMLElement;
}

export function pageElements(doc: Document = document): PageElements {
  const get = (id: string): HTMLElement => {
    const el = doc.getElementById(id);
    // index.html and this list go together: a missing one is a bug in the page.
    if (!el) throw new Error(`index.html has no #${id}`);
    return el;
  };
  return { app: get("app"), hud: get("hud"), message: get("message"), fatal: get("fatal"), loading: get("loading") };
}
