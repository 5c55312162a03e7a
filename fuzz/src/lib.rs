//! UP's fuzz targets as library functions: each module's `check` takes one
//! input and panics when a property fails. The cargo-fuzz binaries
//! (`fuzz_targets/`, nightly) call them on what libFuzzer makes up; the
//! tests below call them on every committed input of `corpus/`, on stable,
//! in `make test` (a regression suite: a target that no longer compiles, or
//! an input that once passed and now fails, fails the build).

pub mod contacts;
pub mod numbers;
pub mod obj;
pub mod scene;
pub mod toi;

#[cfg(test)]
mod corpus_tests;
