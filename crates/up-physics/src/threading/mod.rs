//! How the step's passes run on rayon's threads, apart from the physics they
//! run: a pass split into tasks or run whole (`tasks`), the tasks' lists
//! joined on several threads (`join`), the solver's colours
//! run stage after stage in one fork-join (`staged`), the pool's threads kept
//! awake through a step (`keep_awake`, which the page may turn off:
//! `keep_awake_switch`), and the capacity the passes' buffers
//! took in a busy step given back (`spare`, whose floors are sized by the
//! tasks' lists), and where each thread's time goes (`thread_times`). Which
//! thread runs which work changes no result.

pub(crate) mod join;
#[cfg(feature = "parallel")]
pub(crate) mod keep_awake;
pub mod keep_awake_switch;
pub(crate) mod spare;
#[cfg(feature = "parallel")]
pub(crate) mod staged;
pub(crate) mod tasks;
pub mod thread_sums;
pub(crate) mod thread_times;
