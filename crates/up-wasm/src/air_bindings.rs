//! The engine's calls for moving air (`air.rs`): the page's air tools'
//! commands, the sources to draw, the field on a grid or at points. A second
//! `impl Engine` block beside lib.rs's, one concern apart.

use wasm_bindgen::prelude::*;

use crate::air::{AirCommand, AirGrid};
use crate::error::{named, CallError, WasmError};
use crate::Engine;

#[wasm_bindgen]
impl Engine {
    /// Applies a command of the page's air tools (`AirCommand`: add a fan,
    /// set its speed, remove it, open the door) to the running world;
    /// refused, with nothing changed, when out of range.
    pub fn apply_air(
        &mut self,
        #[wasm_bindgen(unchecked_param_type = "AirCommand")] command: JsValue,
    ) -> Result<(), CallError> {
        // Read here rather than by tsify's conversion, so that a command the
        // engine does not know is refused like any bad argument.
        let command = serde_wasm_bindgen::from_value::<AirCommand>(command)
            .map_err(|e| WasmError::BadArgument(format!("air command: {e}")));
        named("apply_air", command.and_then(|c| self.state.apply_air(c)))
    }

    /// Writes every air source (jets, then draughts; `AIR_SOURCE_FLOATS`
    /// each) for `air_sources_ptr`; returns how many sources.
    pub fn write_air_sources(&mut self) -> Result<u32, CallError> {
        named("write_air_sources", self.state.write_air_sources()).map(|n| n as u32)
    }

    pub fn air_sources_ptr(&self) -> *const f32 {
        self.state.air.sources.as_ptr()
    }

    /// Samples the air now at the centres of `nx`·`ny`·`nz` cells tiling the
    /// room's bounds (`AIR_GRID_FLOATS` a cell, x fastest, then y, then z)
    /// for `air_grid_ptr`; says where (`AirGrid`).
    pub fn write_air_grid(&mut self, nx: u32, ny: u32, nz: u32) -> Result<AirGrid, CallError> {
        named("write_air_grid", self.state.write_air_grid([nx, ny, nz]))
    }

    pub fn air_grid_ptr(&self) -> *const f32 {
        self.state.air.grid.as_ptr()
    }

    /// The air's velocity now (m/s) at each point of `points` (x, y, z each,
    /// m), for `air_points_ptr` (x, y, z each); returns how many points.
    pub fn write_air_at(&mut self, points: &[f32]) -> Result<u32, CallError> {
        named("write_air_at", self.state.write_air_at(points)).map(|n| n as u32)
    }

    pub fn air_points_ptr(&self) -> *const f32 {
        self.state.air.points.as_ptr()
    }
}
