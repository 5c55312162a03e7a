//! The benchmark scene: the original room's shape scaled with the number of
//! balloons, so that every size of the benchmark does the same work per
//! balloon — a pile about three layers deep under the pyramidal ceiling.
//!
//! Scaling rule (documented in docs/benchmarks.md):
//! - The room keeps the original's proportions: square floor of side `W`,
//!   walls `W/2` high, pyramid apex `W/4` above the walls (6, 3, 1.5 m at W = 6).
//! - One layer of balloons under the ceiling holds the floor area over the
//!   area of a hexagonally packed circle of the balloon's diameter `d`:
//!   `W² / (d²·√3/2)`. `W` is chosen so that N balloons make `PILE_LAYERS` (3)
//!   such layers: `W = d·√(N·(√3/2) / 3)`; 4.8 m at 1 000, 15 m at 10 000,
//!   48 m at 100 000 (d = 0.28 m).
//! - The balloons start on the spawn grid of `build::spawn` (a jittered grid
//!   of cells as wide as a balloon's bounding cube), layer upon layer from the
//!   floor. Where that grid needs more room than the rule gives (below a few
//!   thousand balloons, since a cell holds 3.3 times a balloon's volume and
//!   the walls are only `W/2` high), `W` grows in 1 % steps until the grid
//!   fits; the pile is then thinner than three layers (2.3 at 1 000,
//!   `BenchLayout::pile_layers`). `W` is at least 1 m (walls of 0.5 m).
//! - Everything else is the default scene: 11″ helium balloons of 5 leaf
//!   spheres, 20 °C air, dt 1/60 s, 4 substeps, sleeping and continuous
//!   collision on. Positions, tilts and turns come from `seed`.

use glam::Vec3;
use up_geom::SplitMix64;

use crate::build::build_group_model;
use crate::build::room::{box_room, Ceiling};
use crate::build::spawn::{place_spheres, Occupancy, SpawnRegion};
use crate::error::SceneError;
use crate::scene::{
    BalloonGroup, CeilingKind, RoomSpec, Scene, MAX_ROOM_SIZE_M, MAX_TOTAL_BALLOONS,
    MIN_ROOM_SIZE_M,
};

/// Layers of balloons the pile under the ceiling should have.
pub const PILE_LAYERS: f32 = 3.0;
/// Room width over wall height, and over the pyramid's apex height (the original's 6 : 3 : 1.5).
const WALL_HEIGHT_PER_WIDTH: f32 = 0.5;
const APEX_HEIGHT_PER_WIDTH: f32 = 0.25;
/// The spawn region keeps this far from the walls and floor, m (as `build::ROOM_MARGIN`).
const ROOM_MARGIN: f32 = 0.01;

/// The room and how the balloons fill it, for `balloons` balloons.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BenchLayout {
    pub balloons: u64,
    /// m: side of the square floor.
    pub room_width_m: f32,
    /// m: floor to the top of the walls (`room_width_m / 2`).
    pub wall_height_m: f32,
    /// m: top of the walls to the apex (`room_width_m / 4`).
    pub apex_height_m: f32,
    /// Layers of hexagonally packed balloons the pile makes under the ceiling (3, or fewer
    /// where the spawn grid needed a wider room).
    pub pile_layers: f32,
}

/// Side of the spawn grid's cell for a balloon whose bounding sphere has
/// `radius` m: its bounding cube plus a gap (as `build::spawn` makes it).
fn spawn_cell(radius: f32) -> f32 {
    2.0 * radius * 1.05 + 0.005
}

/// Balloons one hexagonally packed layer holds over a floor of side `width`, for diameter `d`.
fn layer_capacity(width: f32, d: f32) -> f32 {
    width * width / (d * d * 0.5 * 3f32.sqrt())
}

/// m: the width the pile rule gives, `d·√(N·(√3/2) / 3)`, at least 1 m.
pub fn pile_width(balloons: u64, diameter_m: f32) -> f32 {
    let w = diameter_m * (balloons.max(1) as f32 * 0.5 * 3f32.sqrt() / PILE_LAYERS).sqrt();
    round_up_cm(w.max(MIN_WIDTH_M))
}

/// Narrowest room allowed (walls of `MIN_ROOM_SIZE_M`).
const MIN_WIDTH_M: f32 = MIN_ROOM_SIZE_M / WALL_HEIGHT_PER_WIDTH;

fn round_up_cm(w: f32) -> f32 {
    (w * 100.0).ceil() / 100.0
}

/// Whether the spawn grid holds `balloons` balloons of bounding radius
/// `radius` below the top of the walls of a room `width` wide (a sufficient
/// condition: the grid may also use the space under the pyramid).
pub fn fits_below_walls(balloons: u64, width: f32, radius: f32) -> bool {
    let cell = spawn_cell(radius);
    let per_row = ((width - 2.0 * ROOM_MARGIN) / cell).floor();
    if per_row < 1.0 {
        return false;
    }
    let layers = balloons.div_ceil((per_row * per_row) as u64);
    ROOM_MARGIN + layers as f32 * cell <= width * WALL_HEIGHT_PER_WIDTH
}

/// The layout of a room `width` wide for `balloons` balloons of diameter `diameter_m`.
pub fn layout_for_width(balloons: u64, width: f32, diameter_m: f32) -> BenchLayout {
    BenchLayout {
        balloons,
        room_width_m: width,
        wall_height_m: width * WALL_HEIGHT_PER_WIDTH,
        apex_height_m: width * APEX_HEIGHT_PER_WIDTH,
        pile_layers: balloons as f32 / layer_capacity(width, diameter_m),
    }
}

/// The narrowest width from `start` upward, in 1 % steps, for which `fits` holds;
/// `None` when not even the widest room does.
pub fn widen_until(start: f32, fits: impl Fn(f32) -> bool) -> Option<f32> {
    let mut width = start;
    loop {
        if fits(width) {
            return Some(width);
        }
        if width >= MAX_ROOM_SIZE_M {
            return None;
        }
        width = round_up_cm(width * 1.01).min(MAX_ROOM_SIZE_M);
    }
}

/// Whether the scene builder places all of the scene's balloons in a room
/// `width` wide: its own spawn layout, run on the room.
fn spawn_fits(scene: &Scene, width: f32, radius: f32) -> bool {
    let count = scene.total_balloons();
    if fits_below_walls(count, width, radius) {
        return true;
    }
    let ceiling = Ceiling::Pyramid {
        apex_height: width * APEX_HEIGHT_PER_WIDTH,
    };
    let Ok(room) = box_room(width, width, width * WALL_HEIGHT_PER_WIDTH, ceiling) else {
        return false;
    };
    let bounds = room.bounds();
    let margin = Vec3::splat(ROOM_MARGIN);
    let (lo, hi) = (bounds.min + margin, bounds.max - margin);
    let region = SpawnRegion {
        min: lo,
        max: Vec3::new(hi.x, lo.y, hi.z),
        top: hi.y,
    };
    let inside = |p: Vec3| room.contains_point(p);
    let placed = place_spheres(
        count as usize,
        radius,
        &region,
        &inside,
        &mut Occupancy::default(),
        &mut SplitMix64::new(scene.sim.seed),
    );
    placed.len() as u64 == count
}

/// The benchmark scene for `balloons` balloons (1 to 200 000), laid out from `seed`.
/// Returns the scene and its layout; `build::build_world` builds it.
pub fn bench_scene(balloons: u64, seed: u64) -> Result<(Scene, BenchLayout), SceneError> {
    let mut scene = Scene::default();
    if balloons == 0 || balloons > MAX_TOTAL_BALLOONS {
        return Err(SceneError::Invalid {
            at: scene.locate("balloons[0].count"),
            expected: format!("1 to {MAX_TOTAL_BALLOONS} balloons for the benchmark scene"),
            found: balloons.to_string(),
        });
    }
    scene.source.name = "<bench scene>".to_string();
    scene.balloons = vec![BalloonGroup {
        count: balloons,
        ..BalloonGroup::default()
    }];
    scene.sim.seed = seed;
    // The balloon decides the room: its diameter and its bounding sphere.
    let model = build_group_model(&scene, 0)?;
    let radius = model.shape.tree.root().sphere().radius;
    let d = scene.balloons[0].diameter();
    let width = widen_until(pile_width(balloons, d), |w| spawn_fits(&scene, w, radius))
        .ok_or_else(|| SceneError::DoesNotFit {
            at: scene.locate("balloons[0].count"),
            requested: balloons,
            placed: 0,
        })?;
    let layout = layout_for_width(balloons, width, d);
    scene.room = RoomSpec {
        width,
        depth: width,
        wall_height: layout.wall_height_m,
        ceiling: CeilingKind::Pyramid,
        apex_height: layout.apex_height_m,
        mesh: None,
    };
    scene.validate()?;
    Ok((scene, layout))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::build::build_world;

    const D: f32 = 0.28;
    const R: f32 = 0.19;

    #[test]
    fn large_rooms_hold_a_three_layer_pile_and_grow_as_the_square_root() {
        for n in [10_000u64, 100_000] {
            let width = pile_width(n, D);
            assert!(fits_below_walls(n, width, R), "{n}: {width}");
            let layout = layout_for_width(n, width, D);
            assert!(
                (layout.pile_layers - PILE_LAYERS).abs() < 0.05,
                "{n}: {layout:?}"
            );
            assert_eq!(layout.wall_height_m, width * 0.5);
            assert_eq!(layout.apex_height_m, width * 0.25);
        }
        let ratio = pile_width(100_000, D) / pile_width(10_000, D);
        assert!((ratio - 10f32.sqrt()).abs() < 0.01, "{ratio}");
    }

    #[test]
    fn small_rooms_widen_until_the_balloons_fit() {
        assert_eq!(pile_width(1, D), 1.0);
        let width = widen_until(pile_width(50, D), |w| fits_below_walls(50, w, R)).unwrap();
        assert!(width > pile_width(50, D) && fits_below_walls(50, width, R));
        assert!(!fits_below_walls(50, width / 1.02, R));
        assert_eq!(widen_until(1.0, |_| false), None);
    }

    #[test]
    fn the_scene_builds_with_every_balloon_inside_and_is_deterministic() {
        let (scene, layout) = bench_scene(300, 7).unwrap();
        assert_eq!(scene.total_balloons(), 300);
        assert_eq!(scene.room.width, layout.room_width_m);
        assert!(layout.pile_layers > 1.0 && layout.pile_layers <= PILE_LAYERS + 0.05);
        let a = build_world(&scene).unwrap();
        let b = build_world(&bench_scene(300, 7).unwrap().0).unwrap();
        assert_eq!(a.world.body_count(), 300);
        assert_eq!(a.world.state_hash(), b.world.state_hash());
        let c = build_world(&bench_scene(300, 8).unwrap().0).unwrap();
        assert_ne!(a.world.state_hash(), c.world.state_hash());
        // One balloon gets the smallest room the scene format allows.
        let (one, _) = bench_scene(1, 1).unwrap();
        assert_eq!(build_world(&one).unwrap().world.body_count(), 1);
    }

    #[test]
    fn a_thousand_balloons_pile_more_than_two_layers_deep() {
        let (scene, layout) = bench_scene(1_000, 1).unwrap();
        assert!(layout.pile_layers > 2.0, "{layout:?}");
        assert_eq!(build_world(&scene).unwrap().world.body_count(), 1_000);
    }

    #[test]
    fn zero_or_too_many_balloons_are_errors() {
        assert!(bench_scene(0, 1).is_err());
        let message = bench_scene(MAX_TOTAL_BALLOONS + 1, 1)
            .unwrap_err()
            .to_string();
        assert!(message.contains("balloons[0].count"), "{message}");
    }
}
