//! Where the balloons of a group that hangs weights over the floor
//! (`hangs_weights`) go: laid before every other group, in staggered layers.
//!
//! The first layer has its knots a ribbon's length and a gap above the
//! floor, so that each weight hangs just clear of it; a group that one layer
//! holds is spread over the floor as `spawn::place_spheres` spreads a layer.
//! A larger group takes the floor's finest grid and, `LAYER_RISE` of a cell
//! higher, a second layer over the gaps between the first's balloons, its
//! ribbons and weights hanging down through those gaps (released, its
//! weights drop that rise to the floor); both are filled row by row from
//! one side, so that the columns take only the floor they need and other
//! groups have the rest, from the floor up. Layers higher still take
//! balloons wherever they fit. A balloon goes only where its bounding sphere
//! and the column its ribbon and weight hang in, from its knot to the floor,
//! are clear of everything laid before (balloons, and the columns of groups
//! laid earlier); the caller reserves each column once the balloon's lean is
//! known (`reserve_column`), so later groups keep out of it.

use glam::Vec3;
use up_geom::SplitMix64;
use up_physics::ribbon::WEIGHT_RADIUS;

use super::spawn::{cell_size, coarse_grids, Grid, Occupancy, SpawnRegion};

/// How far a weight of the first layer hangs above the floor, m: it drops
/// onto the floor when released.
pub(super) const WEIGHT_HANG_GAP: f32 = WEIGHT_RADIUS + 0.01;
/// Radius of the column kept clear around a hanging ribbon and its weight, m.
pub(super) const COLUMN_RADIUS: f32 = WEIGHT_RADIUS + 0.01;
/// Rise from one layer to the next, in cells: a balloon over the gap between
/// four below clears them at √½ of a cell; the rest is room for the jitter.
const LAYER_RISE: f32 = 0.8;

/// A hanging group's balloon, as the layout sees it.
pub(super) struct Hanging {
    /// The balloon's bounding sphere's radius, m.
    pub radius: f32,
    /// The knot, from the bounding sphere's centre, the balloon upright, m.
    pub knot: Vec3,
    /// The ribbon's length, m.
    pub ribbon_length: f32,
    /// Most a balloon leans, degrees: its knot swings by up to the sine of
    /// this times its distance from the centre.
    pub tilt_deg: f32,
}

/// A hanging group laid: its bounding spheres' centres (fewer than asked
/// when the room holds no more) and how many layers they took.
pub(super) struct HangingLayout {
    pub centres: Vec<Vec3>,
    pub layers: usize,
}

/// A lattice of candidate centres: `grid`'s cells, shifted by `shift` of a
/// cell along x and z (½: the gaps between the cells' centres).
#[derive(Clone, Copy)]
struct Lattice {
    grid: Grid,
    shift: f32,
}

/// Lays `count` balloons of `hanging` over `region`'s footprint, the floor
/// at `floor`, no higher than `region.top`; `inside` says whether a point is
/// inside the room. Each layer takes the coarsest grid that holds what is
/// left, else the floor's finest grid or its gaps, whichever holds more.
pub(super) fn lay_hanging(
    count: usize,
    hanging: &Hanging,
    region: &SpawnRegion,
    floor: f32,
    inside: &dyn Fn(Vec3) -> bool,
    occupied: &mut Occupancy,
    rng: &mut SplitMix64,
) -> HangingLayout {
    let r = hanging.radius;
    let c = cell_size(r);
    let mut layout = HangingLayout {
        centres: Vec::with_capacity(count),
        layers: 0,
    };
    let (width, depth) = (region.max.x - region.min.x, region.max.z - region.min.z);
    let (nx, nz) = ((width / c).floor() as usize, (depth / c).floor() as usize);
    if nx == 0 || nz == 0 || count == 0 {
        return layout;
    }
    let fine = Grid {
        nx,
        nz,
        cell_x: width / nx as f32,
        cell_z: depth / nz as f32,
    };
    let gaps = Lattice {
        grid: Grid {
            nx: nx - 1,
            nz: nz - 1,
            ..fine
        },
        shift: 0.5,
    };
    let knot_y = floor + hanging.ribbon_length + WEIGHT_HANG_GAP;
    let lowest = (knot_y - hanging.knot.y).max(region.min.y + 0.5 * c);
    let check = Check {
        hanging,
        region,
        floor,
        cell: c,
        inside,
        // The knot swings sideways with the lean.
        column_radius: COLUMN_RADIUS + hanging.knot.length() * hanging.tilt_deg.to_radians().sin(),
    };
    let mut layer = 0;
    let fine_lattice = Lattice {
        grid: fine,
        shift: 0.0,
    };
    let first = check.usable(&fine_lattice, lowest, occupied, rng).len();
    if count > first {
        // More than a layer holds: the floor's finest grid and its gaps a
        // rise above, filled row by row from one side, so that the
        // columns take only the floor they need and other groups have the rest.
        let upper = lowest + LAYER_RISE * c;
        for iz in 0..nz {
            let rows = [
                (fine_lattice, iz, lowest),
                (gaps, iz.wrapping_sub(1), upper),
            ];
            for (lattice, row, y) in rows {
                if row >= lattice.grid.nz {
                    continue;
                }
                for ix in 0..lattice.grid.nx {
                    if layout.centres.len() == count {
                        break;
                    }
                    let centre = check.centre(&lattice, ix, row, y, rng);
                    if check.fits(centre, occupied) {
                        occupied.insert(centre, r);
                        layout.centres.push(centre);
                        layout.layers = layout.layers.max(usize::from(y > lowest) + 1);
                    }
                }
            }
        }
        layer = 2;
    }
    loop {
        let y = lowest + layer as f32 * LAYER_RISE * c;
        let need = count - layout.centres.len();
        if need == 0 || y + 0.5 * c > region.top {
            break;
        }
        let mut lattices: Vec<Lattice> = if need < nx * nz {
            coarse_grids(need, width, depth, c)
                .into_iter()
                .map(|grid| Lattice { grid, shift: 0.0 })
                .collect()
        } else {
            Vec::new()
        };
        lattices.push(fine_lattice);
        lattices.push(gaps);
        let mut best: Vec<(usize, Vec3)> = Vec::new();
        for lattice in lattices {
            let cells = check.usable(&lattice, y, occupied, rng);
            let enough = cells.len() >= need;
            if cells.len() > best.len() {
                best = cells;
            }
            if enough {
                break;
            }
        }
        if best.len() > need {
            rng.shuffle(&mut best);
            best.truncate(need);
            best.sort_unstable_by_key(|&(cell, _)| cell);
        }
        if !best.is_empty() {
            layout.layers = layer + 1;
        }
        for (_, centre) in best {
            occupied.insert(centre, r);
            layout.centres.push(centre);
        }
        layer += 1;
    }
    layout
}

/// What a candidate centre must be clear of.
struct Check<'a> {
    hanging: &'a Hanging,
    region: &'a SpawnRegion,
    floor: f32,
    cell: f32,
    inside: &'a dyn Fn(Vec3) -> bool,
    column_radius: f32,
}

impl Check<'_> {
    /// The lattice's cells at height `y` (their index and jittered centre)
    /// where a balloon fits: its cell inside the room, its bounding sphere and
    /// a gap clear of every sphere placed, and its ribbon's column too.
    fn usable(
        &self,
        lattice: &Lattice,
        y: f32,
        occupied: &Occupancy,
        rng: &mut SplitMix64,
    ) -> Vec<(usize, Vec3)> {
        let grid = &lattice.grid;
        let mut cells = Vec::new();
        for iz in 0..grid.nz {
            for ix in 0..grid.nx {
                let centre = self.centre(lattice, ix, iz, y, rng);
                if self.fits(centre, occupied) {
                    cells.push((ix + iz * grid.nx, centre));
                }
            }
        }
        cells
    }

    /// The centre of the lattice's cell (`ix`, `iz`) at height `y`, jittered
    /// within the cell's slack as `spawn` jitters.
    fn centre(
        &self,
        lattice: &Lattice,
        ix: usize,
        iz: usize,
        y: f32,
        rng: &mut SplitMix64,
    ) -> Vec3 {
        let r = self.hanging.radius;
        let grid = &lattice.grid;
        let slack_x = (grid.cell_x - 2.0 * r) * 0.5 * 0.9;
        let slack_z = (grid.cell_z - 2.0 * r) * 0.5 * 0.9;
        Vec3::new(
            self.region.min.x
                + (ix as f32 + 0.5 + lattice.shift) * grid.cell_x
                + rng.range(-slack_x, slack_x),
            y,
            self.region.min.z
                + (iz as f32 + 0.5 + lattice.shift) * grid.cell_z
                + rng.range(-slack_z, slack_z),
        )
    }

    /// Whether a balloon fits at `centre`: its cell inside the room, its
    /// bounding sphere and a gap clear of every sphere placed, and the
    /// column its ribbon and weight hang in too.
    fn fits(&self, centre: Vec3, occupied: &Occupancy) -> bool {
        let r = self.hanging.radius;
        // Half the gap the grid keeps between neighbours' spheres.
        let gap = 0.25 * (self.cell - 2.0 * r);
        let knot = centre + self.hanging.knot;
        self.cube_inside(centre)
            && !occupied.overlaps_sphere(centre, r + gap)
            && !occupied.overlaps_column(knot.x, knot.z, self.floor, knot.y, self.column_radius)
    }

    /// Whether the cell's cube about `centre` is inside the room (its eight
    /// corners and centre), as `spawn` asks of a cell.
    fn cube_inside(&self, centre: Vec3) -> bool {
        let half = 0.5 * self.cell;
        (self.inside)(centre)
            && (0..8).all(|k: u32| {
                let sign = |bit: u32| if k & bit == 0 { -half } else { half };
                (self.inside)(centre + Vec3::new(sign(1), sign(2), sign(4)))
            })
    }
}

/// Reserves the column a ribbon and its weight hang in, from `knot` down to
/// `floor`, as a stack of spheres a weight's width and a gap across.
pub(super) fn reserve_column(occupied: &mut Occupancy, knot: Vec3, floor: f32) {
    let mut at = knot;
    while at.y > floor {
        occupied.insert(at, COLUMN_RADIUS);
        at.y -= COLUMN_RADIUS;
    }
}
