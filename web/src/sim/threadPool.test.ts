import { describe, expect, it } from "vitest";
import { DEFAULT_POOL, MAX_THREADS, NOT_ISOLATED_TEXT, defaultThreads, keepThreadsAwake, moduleUrl, requestedPool, requestedThreads } from "./threadPool";
import { threadsText } from "../ui/hud";

describe("the thread count", () => {
  it("defaults to the machine's cores less one, at least one, at most the page's bound", () => {
    expect(defaultThreads(8)).toBe(7);
    expect(defaultThreads(2)).toBe(1);
    expect(defaultThreads(1)).toBe(1);
    expect(defaultThreads(undefined)).toBe(1);
    expect(defaultThreads(0)).toBe(1);
    expect(defaultThreads(1.5)).toBe(1);
    expect(defaultThreads(1000)).toBe(MAX_THREADS);
  });

  it("is the address's `threads` when it is an integer in range", () => {
    expect(requestedThreads("?threads=4", 2)).toEqual({ threads: 4, error: null });
    expect(requestedThreads("?test&threads=1", 16)).toEqual({ threads: 1, error: null });
    expect(requestedThreads(`?threads=${MAX_THREADS}`, 2)).toEqual({ threads: MAX_THREADS, error: null });
    expect(requestedThreads("?test", 6)).toEqual({ threads: 5, error: null });
  });

  it("refuses any other value with a message naming it and the range, and uses the default", () => {
    for (const bad of ["0", "-2", "2.5", "abc", "", " ", `${MAX_THREADS + 1}`, "1e9", "NaN"]) {
      const r = requestedThreads(`?threads=${encodeURIComponent(bad)}`, 4);
      expect(r.threads, bad).toBe(3);
      expect(r.error, bad).toBe(`The address's threads=${bad} is not a thread count: expected an integer from 1 to ${MAX_THREADS}. Using 3.`);
    }
  });
});

describe("the module", () => {
  const single = "http://localhost:8080/app/wasm/up_wasm.wasm";
  it("is the threaded one, next to the single-threaded one, only on an isolated page with more than one thread", () => {
    expect(moduleUrl(single, 2, true)).toBe("http://localhost:8080/app/wasm/threads/up_wasm.wasm");
    expect(moduleUrl(single, 1, true)).toBe(single);
    expect(moduleUrl(single, 8, false)).toBe(single);
  });

  it("is named in the HUD: the threads, or one line saying the page is not isolated", () => {
    expect(threadsText(3, true)).toBe("Threads: 3");
    expect(threadsText(1, false)).toBe(NOT_ISOLATED_TEXT);
  });
});

describe("the pool's settings", () => {
  it("are the address's `pool` and `spin` where valid, each else the default", () => {
    expect(requestedPool("?threads=2")).toEqual(DEFAULT_POOL);
    expect(requestedPool("?pool=beside&spin=1")).toEqual({ here: false, spin: "on" });
    expect(requestedPool("?pool=here&spin=0")).toEqual({ here: true, spin: "off" });
    expect(requestedPool("?spin=auto")).toEqual({ here: DEFAULT_POOL.here, spin: "auto" });
    expect(requestedPool("?pool=elsewhere&spin=2")).toEqual(DEFAULT_POOL);
  });

  it("spin as asked, or by themselves only where they leave the page's drawing a core", () => {
    const auto = { here: true, spin: "auto" } as const;
    expect(keepThreadsAwake(auto, 2, 2, true)).toBe(false);
    expect(keepThreadsAwake(auto, 2, 2, false)).toBe(true);
    expect(keepThreadsAwake(auto, 3, 4, true)).toBe(true);
    expect(keepThreadsAwake(auto, 4, 4, true)).toBe(false);
    expect(keepThreadsAwake(auto, 2, undefined, true)).toBe(false);
    expect(keepThreadsAwake({ here: true, spin: "on" }, 2, 2, true)).toBe(true);
    expect(keepThreadsAwake({ here: false, spin: "off" }, 2, 8, false)).toBe(false);
  });
});
