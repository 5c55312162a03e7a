//! UP against Rapier on the benchmark scene (`up_scene::bench_scene`):
//! the same room, balloons, masses, forces, timestep and substeps in both
//! engines, stepped alternately in one process. docs/benchmarks.md says how
//! each quantity is matched and measured.

pub mod core_probe;
pub mod engine;
pub mod measure;
pub mod output;
pub mod plot;
pub mod rapier_engine;
pub mod report;
pub mod ribbon_report;
pub mod ribbons;
pub mod rss;
pub mod run;
pub mod scene_data;
pub mod scene_export;
pub mod stats;
pub mod step_times;
pub mod system_info;
pub mod thread_times;
pub mod up_engine;
