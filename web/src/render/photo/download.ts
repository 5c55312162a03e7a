// Saving a file from the page: a blob handed to the browser's downloads
// through a temporary link, named with the local date and time.

/** `<prefix>-2026-12-02T03-04-05.<ext>`: the moment in a name every file system takes. */
export function timestampName(prefix: string, ext: string, at: Date = new Date()): string {
  const pad = (n: number) => String(n).padStart(2, "0");
  const date = `${at.getFullYear()}-${pad(at.getMonth() + 1)}-${pad(at.getDate())}`;
  const time = `${pad(at.getHours())}-${pad(at.getMinutes())}-${pad(at.getSeconds())}`;
  return `${prefix}-${date}T${time}.${ext}`;
}

/** Downloads `blob` as `name`. */
export function downloadBlob(blob: Blob, name: string): void {
  const a = document.createElement("a");
  a.href = URL.createObjectURL(blob);
  a.download = name;
  a.click();
  // The download has taken its copy by then.
  setTimeout(() => URL.revokeObjectURL(a.href), 10_000);
}
