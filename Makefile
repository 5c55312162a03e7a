# UP — one entry point for building, running and testing.
#   make run    set up, build everything, serve the app on http://localhost:$(PORT)
#   make test   set up, lint, run every test (Rust, web unit, browser end-to-end)
#   make bench  UP against Rapier (native and in Node) at 1k and 10k balloons, UP alone at 100k;
#               writes docs/benchmarks.md and docs/benchmarks.svg (tens of minutes)
#   make bench-ribbons  the same with a ribbon on every balloon (Rapier: chains of balls);
#               writes the ribbons' table at the end of docs/benchmarks.md (half an hour or more)
#   make measure  the web app in headless Chromium at BALLOONS (10000) on each of THREADS (1,2):
#               physics per step, the main thread's frame work, input, state hash (one JSON line);
#               RIBBONS=1 ties the default scene's 1.5 m ribbon on every balloon, RIBBONS=both
#               measures without and with in turn on each thread count (their ratio from one run);
#               each thread's busy/barrier/idle time per stage; ROUNDS=3 alternates three times
#   make fuzz   run every cargo-fuzz target for FUZZ_SECONDS each (pinned nightly + cargo-fuzz);
#               `make test` runs the targets over their committed corpus on stable
#   make soak   the long run of issue 7: 10,000 balloons for an hour of simulated time
#   make render a scene's run rendered by Blender's Cycles on the CPU, headless: PNG frames (and an
#               MP4 of several) in renders/SCENE/; installs Debian's blender (not part of make test)
# Every target installs what it needs, idempotently.

SHELL := /bin/bash
.SHELLFLAGS := -eu -o pipefail -c
PORT ?= 8080
CARGO ?= cargo
WASM_TARGET := wasm32-unknown-unknown
WASM_OUT := web/public/wasm/up_wasm.wasm
# The threaded module (Web Workers sharing one memory) for cross-origin isolated
# pages; up_wasm.wasm stays the module of the others. Its glue and the worker
# script of wasm-bindgen-rayon go to their own directory.
WASM_THREADS_DIR := web/public/wasm/threads
WASM_THREADS_OUT := $(WASM_THREADS_DIR)/up_wasm.wasm
# Threads in wasm need a std built with atomics (-Z build-std), which only a
# nightly does: one pinned nightly, for this build only.
WASM_THREADS_TOOLCHAIN := nightly-2026-05-19
# The JS glue must come from the wasm-bindgen-cli of the version Cargo.lock holds.
WASM_BINDGEN_VERSION := $(shell sed -n '/^name = "wasm-bindgen"$$/{n;s/^version = "\(.*\)"$$/\1/p;}' Cargo.lock)
RUST_SOURCES := $(shell find crates -name '*.rs' -o -name Cargo.toml) Cargo.toml Cargo.lock .cargo/config.toml
# No npm install ever downloads a browser: the tests run Debian's chromium (setup-browser).
export PLAYWRIGHT_SKIP_BROWSER_DOWNLOAD := 1
WEB_SOURCES := $(shell find web/src web/index.html web/vite.config.* web/tsconfig*.json web/scripts -type f 2>/dev/null) $(shell find assets -type f 2>/dev/null)

.PHONY: run build test lint test-rust test-fuzz-corpus test-web test-e2e test-determinism bench bench-ribbons measure fuzz soak setup setup-rust setup-wasm-threads setup-web setup-browser setup-bench setup-blender setup-pyflakes test-render render serve clean

run: build
	@echo "UP is being served on http://localhost:$(PORT)  (Ctrl-C stops it)"
	cd web && npm run --silent serve -- --port $(PORT)

build: setup $(WASM_OUT) $(WASM_THREADS_OUT) web/dist/index.html
	$(CARGO) build --release -p up-cli

setup: setup-rust setup-wasm-threads setup-web

setup-rust:
	@rustup target list --installed 2>/dev/null | grep -qx $(WASM_TARGET) || rustup target add $(WASM_TARGET)
	@rustup component list --installed 2>/dev/null | grep -q '^clippy' || rustup component add clippy
	@rustup component list --installed 2>/dev/null | grep -q '^rustfmt' || rustup component add rustfmt
	@wasm-bindgen --version 2>/dev/null | grep -qx 'wasm-bindgen $(WASM_BINDGEN_VERSION)' || \
	  $(CARGO) install wasm-bindgen-cli --version $(WASM_BINDGEN_VERSION) --locked --no-default-features

# The pinned nightly with the standard library's sources (build-std), installed once.
setup-wasm-threads:
	@rustup toolchain list | grep -q '^$(WASM_THREADS_TOOLCHAIN)-' && \
	  rustup component list --installed --toolchain $(WASM_THREADS_TOOLCHAIN) | grep -q '^rust-src' || \
	  rustup toolchain install $(WASM_THREADS_TOOLCHAIN) --profile minimal --component rust-src

# npm ci only when the lock file changed since the last install.
setup-web: web/node_modules/.installed

web/node_modules/.installed: web/package.json web/package-lock.json
	cd web && npm ci --no-audit --no-fund
	touch $@

# Debian's chromium for the browser tests (never a browser download).
setup-browser:
	@command -v chromium >/dev/null 2>&1 || { \
	  echo "Installing Debian's chromium for the browser tests"; \
	  SUDO=$$( [ "$$(id -u)" = 0 ] || echo sudo ); \
	  $$SUDO apt-get update -qq && DEBIAN_FRONTEND=noninteractive $$SUDO apt-get install -y -qq chromium >/dev/null; }

$(WASM_OUT): $(RUST_SOURCES) | setup-rust
	# No debug info in the wasm (10.7 MB with it, 0.9 MB without).
	CARGO_PROFILE_RELEASE_DEBUG=0 $(CARGO) build --release -p up-wasm --target $(WASM_TARGET)
	# up_wasm.js (glue), up_wasm.d.ts (types), and the module, renamed from
	# up_wasm_bg.wasm: the page and the tools pass its bytes to initSync.
	wasm-bindgen --target web --out-dir $(dir $@) target/$(WASM_TARGET)/release/up_wasm.wasm
	# The module imports only what the glue provides (up-wasm defines the stage
	# clock): an import from "env" would be a module no browser resolves.
	! grep -n 'from "env"' $(dir $@)up_wasm.js
	mv $(dir $@)up_wasm_bg.wasm $@
	mv $(dir $@)up_wasm_bg.wasm.d.ts $(dir $@)up_wasm.wasm.d.ts

# The threaded module: the same engine with up-physics' `parallel` passes on
# rayon's pool. Atomics, bulk memory and mutable globals make the memory
# shareable (simd128 as the other build: RUSTFLAGS replaces .cargo/config.toml's
# flags); std is rebuilt with them, with panic=abort (build-std cannot unwind on
# wasm). Its own target directory keeps the stable build's artifacts as they are.
# The module's link (this rustc leaves it to us): a shared memory that the
# glue creates and hands to every worker, and the thread-local storage's
# exports, with which wasm-bindgen gives each worker its own. The memory may
# grow to 2 GiB: 10,000 balloons take a few hundred MB, and a shared memory
# cannot move, so browsers reserve its maximum up front.
WASM_THREADS_LINK := --shared-memory --import-memory --max-memory=2147483648 \
  --export=__wasm_init_tls --export=__tls_size --export=__tls_align --export=__tls_base
$(WASM_THREADS_OUT): $(RUST_SOURCES) | setup-rust setup-wasm-threads
	RUSTFLAGS='-C target-feature=+atomics,+bulk-memory,+mutable-globals,+simd128' \
	CARGO_PROFILE_RELEASE_PANIC=abort CARGO_PROFILE_RELEASE_DEBUG=0 \
	  rustup run $(WASM_THREADS_TOOLCHAIN) cargo rustc --release -p up-wasm --lib --features threads \
	  --target $(WASM_TARGET) --target-dir target/wasm-threads -Z build-std=panic_abort,std -- \
	  $(addprefix -C link-arg=,$(WASM_THREADS_LINK))
	rm -rf $(WASM_THREADS_DIR)
	wasm-bindgen --target web --out-dir $(WASM_THREADS_DIR) target/wasm-threads/$(WASM_TARGET)/release/up_wasm.wasm
	! grep -n 'from "env"' $(WASM_THREADS_DIR)/up_wasm.js
	mv $(WASM_THREADS_DIR)/up_wasm_bg.wasm $@
	mv $(WASM_THREADS_DIR)/up_wasm_bg.wasm.d.ts $(WASM_THREADS_DIR)/up_wasm.wasm.d.ts

web/dist/index.html: $(WASM_OUT) $(WASM_THREADS_OUT) $(WEB_SOURCES) web/node_modules/.installed
	cd web && npm run --silent build

serve:
	cd web && npm run --silent serve -- --port $(PORT)

lint: setup-rust setup-pyflakes
	pyflakes3 tools/render
	$(CARGO) fmt --all -- --check
	$(CARGO) clippy --workspace --all-targets --release -- -D warnings
	$(CARGO) fmt --manifest-path fuzz/Cargo.toml --all -- --check
	$(CARGO) clippy --manifest-path fuzz/Cargo.toml --target-dir target --all-targets --release -- -D warnings

test-rust: test-fuzz-corpus
	$(CARGO) test --workspace --release

# The fuzz targets cannot rot unseen: their bodies are fuzz/'s library
# (fuzz/src, one `check(bytes)` a target; the cargo-fuzz binaries only call
# them), which builds on stable, and its tests run every committed input of
# fuzz/corpus/ through them: a regression suite of what the fuzzer found, so
# more than a compile check (≈ 10 s, after a first build of ≈ 2 min). The
# lint above checks the binaries too; only libFuzzer's instrumented build
# needs the nightly (`make fuzz`). fuzz/ is a workspace of its own
# (cargo-fuzz's layout); it shares target/ with the main one.
test-fuzz-corpus:
	$(CARGO) test --manifest-path fuzz/Cargo.toml --target-dir target --release --lib

# The web tests load the built module (the contract test checks both sides agree).
test-web: setup-web $(WASM_OUT)
	cd web && npm test

# @playwright/test against the built app in Debian's chromium (web/playwright.config.ts);
# the HTML report goes to web/e2e/out/report and is never served (a run ends on its own, CI or not).
test-e2e: setup-browser build
	cd web && npx tsc --noEmit -p e2e && npx playwright test

# The WebAssembly build, run in Node, must end a small scene with the native run's state hash,
# and agree with it body by body at every step (where not, it names the first step and body).
test-determinism: build
	node --test web/determinism/bodyHashes.test.mjs
	node web/determinism/check.mjs
	node web/determinism/check.mjs web/determinism/fan-scene.toml

# The render script, run by Blender on a short export of the default room (tiny, few samples),
# where Blender is installed (make render installs it); skipped, saying so, where it is not.
test-render:
	@if command -v $(BLENDER) >/dev/null 2>&1; then \
	  $(MAKE) --no-print-directory setup-blender && $(CARGO) build --release -p up-cli && \
	  python3 tools/render/test_render.py --blender $(BLENDER) --up target/release/up; \
	else echo "test-render: skipped, Blender is not installed (make render installs Debian's blender)"; fi

test: lint test-rust test-web test-e2e test-determinism test-render
	@echo "make test: all suites passed"

FUZZ_SECONDS ?= 300
SOAK_ARGS ?= --balloons 10000 --seconds 3600

setup-bench: web/bench/node_modules/.installed

web/bench/node_modules/.installed: web/bench/package.json web/bench/package-lock.json
	cd web/bench && npm ci --no-audit --no-fund
	touch $@

bench: setup-rust setup-bench $(WASM_OUT)
	$(CARGO) build --release -p up-bench -p up-cli
	target/release/up bench --balloons 1000 --steps 600
	target/release/up-bench report --node

# 10,000 balloons for 300 steps: the start, the rise and the first arrivals (Rapier takes
# seconds a step there); Rapier's multibody chains at 100 balloons for two seconds.
bench-ribbons: setup-rust
	$(CARGO) build --release -p up-bench
	target/release/up-bench report --ribbons --sizes 1000,10000 --multibody-sizes 100 --steps 600,300,120

# The page in headless Chromium, once per thread count on the same scene: physics per step over
# MEASURE_STEPS steps (300: the rise, the arrival under the ceiling, the pile going to sleep),
# the main thread's frame work, input delay, the state hash (equal on all), and each thread's
# busy, barrier and idle time in each stage. RIBBONS: 0 (free balloons), 1 (each on the default
# scene's ribbon) or both (without and with, in turn). ROUNDS: the whole sequence repeated, so
# that the settings alternate; MEASURE_ARGS: more of measure.mjs's options (--pool, --spin).
BALLOONS ?= 10000
THREADS ?= 1,2
MEASURE_STEPS ?= 300
RIBBONS ?= 0
ROUNDS ?= 1
MEASURE_ARGS ?=
measure: setup-browser build
	cd web && node e2e/measure.mjs --balloons $(BALLOONS) --threads $(THREADS) --steps $(MEASURE_STEPS) --seconds 10 --ribbons=$(RIBBONS) --rounds $(ROUNDS) $(MEASURE_ARGS)

# cargo-fuzz on the pinned nightly (the threaded wasm build's); fuzz/run.sh says what it runs.
fuzz: setup-wasm-threads
	@cargo +$(WASM_THREADS_TOOLCHAIN) fuzz --version >/dev/null 2>&1 || cargo install cargo-fuzz --locked
	UP_NIGHTLY=$(WASM_THREADS_TOOLCHAIN) fuzz/run.sh $(FUZZ_SECONDS)

soak: setup-rust
	$(CARGO) run --release -p up-cli -- soak $(SOAK_ARGS)

# Debian's blender for make render, with python3-numpy, which its glTF importer needs and the
# package does not pull in. Never a download from elsewhere.
BLENDER ?= blender
setup-blender:
	@command -v $(BLENDER) >/dev/null 2>&1 && dpkg -s python3-numpy >/dev/null 2>&1 || { \
	  echo "Installing Debian's blender (and python3-numpy for its glTF importer) for make render"; \
	  SUDO=$$( [ "$$(id -u)" = 0 ] || echo sudo ); \
	  $$SUDO apt-get update -qq && DEBIAN_FRONTEND=noninteractive $$SUDO apt-get install -y -qq blender python3-numpy >/dev/null; }

# Debian's pyflakes for the render script's lint.
setup-pyflakes:
	@command -v pyflakes3 >/dev/null 2>&1 || { \
	  SUDO=$$( [ "$$(id -u)" = 0 ] || echo sudo ); \
	  $$SUDO apt-get update -qq && DEBIAN_FRONTEND=noninteractive $$SUDO apt-get install -y -qq pyflakes3 >/dev/null; }

# A scene's run (up export-gltf) rendered by Cycles on the CPU through tools/render/render_gltf.py:
# Blender's glTF importer, then the page's photo lights and sky. FRAME=N renders one frame, FRAMES=A-B
# several (and clip.mp4 of them), at FPS from the run's start; SECONDS is how much of the run is
# exported (by default just enough for the last frame). CAMERA=home views it from the page's home
# view rather than the file's camera. Frames and the .glb go to RENDER_DIR. Blender takes its
# Python's prefix from the first python3.x on PATH: the system's, for its numpy.
SCENE ?= assets/scenes/default.toml
FPS ?= 30
FRAME ?= 120
FRAMES ?=
SAMPLES ?= 64
SIZE ?= 960x600
CAMERA ?= file
RENDER_DIR ?= renders/$(basename $(notdir $(SCENE)))
render: setup-blender
	$(CARGO) build --release -p up-cli
	@frames='$(or $(FRAMES),$(FRAME))'; last=$${frames##*-}; \
	seconds='$(SECONDS)'; [ -n "$$seconds" ] || seconds=$$(( last / $(FPS) + 1 )); \
	mkdir -p $(RENDER_DIR); \
	echo "Exporting $$seconds s of $(SCENE) at $(FPS) fps to $(RENDER_DIR)/run.glb"; \
	target/release/up export-gltf $(SCENE) $(RENDER_DIR)/run.glb --seconds $$seconds --fps $(FPS); \
	PATH=/usr/bin:$$PATH $(BLENDER) -b --factory-startup --python-exit-code 1 --python tools/render/render_gltf.py -- \
	  --glb $(RENDER_DIR)/run.glb --out $(RENDER_DIR) --frames $$frames --samples $(SAMPLES) --size $(SIZE) --fps $(FPS) --camera $(CAMERA)

clean:
	$(CARGO) clean
	rm -rf web/dist web/node_modules $(dir $(WASM_OUT))
