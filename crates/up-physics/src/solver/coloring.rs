//! Graph colouring of the contact constraints (the idea of Box2D v3's
//! constraint graph): no two constraints of one colour move the same body, so
//! the constraints of a colour can be solved at once, in any order and on any
//! number of threads, with the same result. Colours are solved one after the
//! other, which keeps the Gauss-Seidel character of the solve.
//!
//! Static bodies (the room, sleeping balloons) never take an impulse, so they
//! do not count as shared. Constraints that find no free colour among the 64
//! (a balloon deep in a big pile has more contacts) overflow into *levels*
//! after the colours: each takes the level after the last one its bodies'
//! earlier overflow constraints took, so every body meets its overflow
//! constraints in the given order, as one serial pass over them would, and
//! the constraints of a level, sharing no moving body, run at once like a
//! colour's with the serial pass's results bit for bit. Past the last level
//! the rest run serially, one constraint a group.
//!
//! Within a colour, the constraints against a fixed body (`Moving::A`: the
//! room or a sleeper on side B; `Moving::B`: on side A) get groups of their
//! own, after those between two moving bodies: the passes then leave the
//! fixed side's lanes alone instead of gathering and updating four bodies
//! that cannot move. A colour's constraints are independent, so where in the
//! colour each goes changes no result.
//!
//! That freedom buys locality on several threads: within each run the
//! constraints are ordered by their first body's *zone* (a slab of the room,
//! `Solver::zones`), so that the same part of every colour, which the same
//! thread takes (`staged`), moves the same bodies, whose states then stay in
//! that thread's cache instead of crossing between cores at every colour.

use super::body_state::BodyState;
use super::lanes::LANES;
use crate::threading::spare::{release_spare, BUFFER_FLOOR};
#[cfg(feature = "parallel")]
use crate::threading::staged::Stages;

/// Colours a body can carry (bits of a `u64`).
const COLORS: usize = 64;

/// Overflow levels after the colours: a big pile's arrival overflows
/// thousands of constraints, which one by one would hold every pass on one
/// thread while the others wait (docs/perf-log.md).
const LEVELS: usize = 192;

/// The colour index of the constraints run serially, after the levels.
const SERIAL: usize = COLORS + LEVELS;

/// Slabs of the room that order a run's constraints (`Coloring::assign`'s
/// `zones`): enough that a thread's share of a colour is a few slabs.
pub(crate) const ZONES: usize = 32;

/// Most groups a block holds (`ColourBlocks`), but for the serial rest and
/// the blocks that join one-block stages in a row.
#[cfg(feature = "parallel")]
pub(crate) const BLOCK_GROUPS: u32 = 64;

/// Fewest groups a thread's part of a stage holds: a stage with fewer than
/// this for each thread stays one block (and joins its one-block
/// neighbours), since a wait at a barrier costs about as much as solving
/// this many groups.
#[cfg(feature = "parallel")]
pub(crate) const MIN_THREAD_GROUPS: u32 = 16;

/// Which sides of a group's constraints can move: every lane of a group alike.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Moving {
    Both,
    /// Side B is fixed (`BodyState::is_fixed`) in every lane.
    A,
    /// Side A is fixed in every lane.
    B,
}

impl Moving {
    const ALL: [Moving; 3] = [Moving::Both, Moving::A, Moving::B];

    /// Whether side `side` (0: A, 1: B) is fixed in every lane.
    #[inline]
    pub fn fixes(self, side: usize) -> bool {
        match self {
            Moving::Both => false,
            Moving::A => side == 1,
            Moving::B => side == 0,
        }
    }

    /// The sides that move, from whether each is fixed.
    fn of(a_fixed: bool, b_fixed: bool) -> Moving {
        match (a_fixed, b_fixed) {
            (false, true) => Moving::A,
            (true, false) => Moving::B,
            _ => Moving::Both,
        }
    }
}

/// The groups of a colour's `runs` as pieces, zone after zone, each zone's
/// pieces in the runs' order, into `pieces`: a stage cut in order into shares
/// then gives each thread a part of the room, whichever sides move.
/// `zone_starts(moving)` holds where each zone starts in that run, in
/// constraints; a group goes with the zone of its last lane, a run's last
/// group, partly filled, with the last zone.
#[cfg(feature = "parallel")]
fn pieces_by_zone<'a>(
    runs: &[ColourRun],
    zone_starts: impl Fn(Moving) -> &'a [u32],
    pieces: &mut Vec<ColourRun>,
) {
    pieces.clear();
    let lanes = LANES as u32;
    let zones = runs.first().map_or(0, |r| zone_starts(r.moving).len());
    for zone in 0..zones {
        for run in runs {
            let starts = zone_starts(run.moving);
            let start = run.start + starts[zone] / lanes;
            let end = starts
                .get(zone + 1)
                .map_or(run.end, |&s| run.start + s / lanes);
            if start < end {
                pieces.push(ColourRun { start, end, ..*run });
            }
        }
    }
}

/// Where run (`color`, `moving`)'s count of zone `zone` is kept in `Coloring::zone_counts`.
fn zone_index(color: usize, moving: Moving, zone: usize, zone_count: usize) -> usize {
    (color * 3 + moving as usize) * zone_count + zone
}

/// Groups `[start, end)` of one colour whose constraints all move `moving`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct ColourRun {
    pub start: u32,
    pub end: u32,
    pub moving: Moving,
}

/// Where each constraint goes, reused from step to step.
#[derive(Clone, Debug, Default)]
pub(crate) struct Coloring {
    /// Colour of each constraint, in the narrowphase's order (from `COLORS`
    /// on the overflow's levels, `SERIAL` the serial rest), the sides it
    /// moves, and its zone.
    color: Vec<(u16, Moving, u8)>,
    /// Colours already used by each body's constraints.
    used: Vec<u64>,
    /// Whether each body moves (takes impulses) and whether it is fixed
    /// (`BodyState::is_fixed`), read once a step rather than per constraint
    /// (empty in a step of fewer constraints than half the bodies: each
    /// constraint's bodies are read instead).
    kind: Vec<(bool, bool)>,
    /// The level after the last one each body's overflow constraints took
    /// (sized only in a step that overflows).
    next_level: Vec<u16>,
    /// Constraints of each zone of each run (colour, sides, zone), then
    /// where the next one of that zone goes in its run.
    zone_counts: Vec<u32>,
    /// Per colour (to `SERIAL`), its constraints for each `Moving`, and
    /// the first group of each run: kept zeroed between calls but for
    /// what the last one used, which it clears (a step of a few contacts
    /// would spend more on clearing every colour than on colouring).
    counts: Vec<[u32; 3]>,
    first_group: Vec<[u32; 3]>,
    /// A colour's runs cut by zone, in zone order (`pieces_by_zone`).
    #[cfg(feature = "parallel")]
    pieces: Vec<ColourRun>,
    /// The groups of `LANES` constraints, colour by colour (levels after
    /// colours), each colour in up to three runs (`Moving::ALL`'s order); the
    /// last run is the serial rest, one constraint per group so that it runs
    /// serially, all as `Moving::Both`.
    pub ranges: Vec<ColourRun>,
    /// For each constraint in the narrowphase's order, its slot: group · `LANES` + lane.
    pub slot: Vec<u32>,
    /// Groups in all.
    pub groups: usize,
    /// The runs cut into blocks for rayon's threads.
    #[cfg(feature = "parallel")]
    pub blocks: ColourBlocks,
    /// Tests only: every overflowing constraint runs serially, one a group
    /// (no levels): the serial order the levels must reproduce.
    #[cfg(test)]
    pub serial_overflow: bool,
}

/// The groups of a pass cut into blocks that tasks take whole (`staged`):
/// a colour (or level) is a stage, its runs cut into blocks of equal size,
/// as few as hold at most `BLOCK_GROUPS` groups each and share evenly among
/// the threads (a multiple of their number), so that each thread's share
/// of a stage is as long as the others'; a stage with fewer than
/// `MIN_THREAD_GROUPS` a thread, and the serial rest, is one block.
/// Consecutive stages of one block each become one block, solved in colour
/// order by one task: the colours' long tail of a few groups each costs no
/// wait between them.
#[cfg(feature = "parallel")]
#[derive(Clone, Debug, Default)]
pub(crate) struct ColourBlocks {
    /// Threads the stages are cut for (0 counts as 1).
    pub threads: u32,
    /// The pieces of runs, in the runs' order; a block is consecutive pieces.
    pub pieces: Vec<ColourRun>,
    /// Block k holds `pieces[piece_end[k - 1]..piece_end[k]]` (from 0 for k = 0).
    pub piece_end: Vec<u32>,
    /// The first block of block k's stage.
    pub stage_first: Vec<u32>,
    /// The stages laid out for the passes (`finish`).
    pub stages: Stages,
}

#[cfg(feature = "parallel")]
impl ColourBlocks {
    /// Empties the blocks, to be cut for `threads` threads.
    fn clear(&mut self, threads: usize) {
        self.threads = threads as u32;
        self.pieces.clear();
        self.piece_end.clear();
        self.stage_first.clear();
    }

    fn release_spare(&mut self) {
        release_spare(&mut self.pieces, BUFFER_FLOOR);
        release_spare(&mut self.piece_end, BUFFER_FLOOR);
        release_spare(&mut self.stage_first, BUFFER_FLOOR);
        self.stages.release_spare();
    }

    /// Lays out the stages once every one is added.
    fn finish(&mut self) {
        self.stages.lay_out(&self.stage_first);
    }

    /// The pieces of block `k`.
    pub fn block(&self, k: usize) -> &[ColourRun] {
        let start = if k == 0 { 0 } else { self.piece_end[k - 1] };
        &self.pieces[start as usize..self.piece_end[k] as usize]
    }

    /// Adds one stage: `runs`, cut into blocks (a block may span runs) as
    /// the type says, or whole if `whole`.
    fn add_stage(&mut self, runs: &[ColourRun], whole: bool) {
        let first_piece = self.pieces.len();
        let first_block = self.piece_end.len();
        let groups: u32 = runs.iter().map(|r| r.end - r.start).sum();
        let threads = self.threads.max(1);
        let blocks = if whole || groups < MIN_THREAD_GROUPS * threads {
            1
        } else {
            threads * groups.div_ceil(threads * BLOCK_GROUPS)
        };
        // Block b ends after groups * (b + 1) / blocks of the stage's groups.
        let end_of = |b: u32| (u64::from(groups) * u64::from(b + 1) / u64::from(blocks)) as u32;
        let (mut block, mut done) = (0, 0);
        for run in runs {
            let mut start = run.start;
            while start < run.end {
                let room = end_of(block) - done;
                let end = run.end.min(start + room);
                self.pieces.push(ColourRun { start, end, ..*run });
                done += end - start;
                if done == end_of(block) {
                    self.piece_end.push(self.pieces.len() as u32);
                    block += 1;
                }
                start = end;
            }
        }
        if *self.piece_end.last().unwrap_or(&(first_piece as u32)) < self.pieces.len() as u32 {
            self.piece_end.push(self.pieces.len() as u32);
        }
        let blocks = self.piece_end.len() - first_block;
        // A one-block stage after a one-block stage joins its block.
        let last_alone =
            first_block > 0 && self.stage_first[first_block - 1] as usize == first_block - 1;
        if blocks == 1 && last_alone {
            self.piece_end.pop();
            *self.piece_end.last_mut().unwrap() = self.pieces.len() as u32;
            return;
        }
        self.stage_first
            .extend(std::iter::repeat_n(first_block as u32, blocks));
    }
}

impl Coloring {
    /// Gives back the capacity this step's constraints left unused (`spare`).
    pub fn release_spare(&mut self) {
        release_spare(&mut self.color, BUFFER_FLOOR);
        release_spare(&mut self.next_level, BUFFER_FLOOR);
        release_spare(&mut self.zone_counts, BUFFER_FLOOR);
        release_spare(&mut self.slot, BUFFER_FLOOR);
        #[cfg(feature = "parallel")]
        self.blocks.release_spare();
        #[cfg(feature = "parallel")]
        release_spare(&mut self.pieces, BUFFER_FLOOR);
    }

    /// Colours the constraints between the body pairs `pairs` greedily
    /// (lowest free colour, in the given order, so room contacts, which come
    /// first, are solved first; then the overflow's levels) and gives each a
    /// slot: colour by colour, the sides it moves within a colour, `LANES` to
    /// a group, in the given order within those, but for `zones`: each
    /// body's zone (below `ZONES`; none: one zone), by which a run's
    /// constraints are ordered first (the first body's; the serial rest keeps
    /// the given order, which it runs in).
    pub fn assign(
        &mut self,
        pairs: impl Iterator<Item = (u32, u32)>,
        states: &[BodyState],
        zones: &[u8],
    ) {
        let zone_count = if zones.is_empty() { 1 } else { ZONES };
        self.used.clear();
        self.used.resize(states.len(), 0);
        self.next_level.clear();
        self.color.clear();
        // Zero but where the last call used them, which it cleared.
        let zone_size = (SERIAL + 1) * 3 * zone_count;
        if self.zone_counts.len() != zone_size {
            self.zone_counts.clear();
            self.zone_counts.resize(zone_size, 0);
        }
        if self.counts.len() != SERIAL + 1 {
            self.counts = vec![[0; 3]; SERIAL + 1];
            self.first_group = vec![[0; 3]; SERIAL + 1];
        }
        let mut counts = std::mem::take(&mut self.counts);
        let mut first_group = std::mem::take(&mut self.first_group);
        // The colours below it hold every constraint but the serial rest's.
        let mut colours_used = 0;
        let kind_of = |s: &BodyState| (s.inv_mass > 0.0, s.is_fixed());
        // A few contacts among many sleepers read only their own bodies.
        let per_constraint = 2 * pairs.size_hint().0 < states.len();
        self.kind.clear();
        if !per_constraint {
            self.kind.extend(states.iter().map(kind_of));
        }
        for (a, b) in pairs {
            let kind = |i: u32| match per_constraint {
                true => kind_of(&states[i as usize]),
                false => self.kind[i as usize],
            };
            let ((a_moves, a_fixed), (b_moves, b_fixed)) = (kind(a), kind(b));
            let taken = if a_moves { self.used[a as usize] } else { 0 }
                | if b_moves { self.used[b as usize] } else { 0 };
            let mut color = (!taken).trailing_zeros() as usize; // COLORS when all are taken
            if color < COLORS {
                let bit = 1u64 << color;
                if a_moves {
                    self.used[a as usize] |= bit;
                }
                if b_moves {
                    self.used[b as usize] |= bit;
                }
            } else {
                color = self.overflow_colour([(a, a_moves), (b, b_moves)], states.len());
            }
            let (sides, zone) = if color < SERIAL {
                let zone = zones.get(a as usize).map_or(0, |&z| z as usize);
                debug_assert!(zone < zone_count, "zone {zone} of {zone_count}");
                (Moving::of(a_fixed, b_fixed), zone)
            } else {
                (Moving::Both, 0)
            };
            self.color.push((color as u16, sides, zone as u8));
            if color < SERIAL {
                colours_used = colours_used.max(color + 1);
            }
            counts[color][sides as usize] += 1;
            self.zone_counts[zone_index(color, sides, zone, zone_count)] += 1;
        }

        // Each zone's first place in its run: the zones' counts summed before it.
        for color in (0..colours_used).chain([SERIAL]) {
            let first = zone_index(color, Moving::Both, 0, zone_count);
            let runs = &mut self.zone_counts[first..first + 3 * zone_count];
            for run in runs.chunks_exact_mut(zone_count) {
                let mut before = 0;
                for count in run {
                    (*count, before) = (before, before + *count);
                }
            }
        }

        // Each run's first group; the serial rest takes a group per constraint.
        self.ranges.clear();
        #[cfg(feature = "parallel")]
        self.blocks.clear(crate::threading::tasks::threads_here());
        let mut start = 0u32;
        // An empty colour adds no run and no stage: only those in use are
        // walked (a step of a few contacts would spend more on the empty ones).
        for color in (0..colours_used).chain([SERIAL]) {
            let counts = &counts[color];
            #[cfg(feature = "parallel")]
            let colour_runs = self.ranges.len();
            for moving in Moving::ALL {
                let count = counts[moving as usize];
                let groups = if color == SERIAL {
                    count
                } else {
                    count.div_ceil(LANES as u32)
                };
                first_group[color][moving as usize] = start;
                if count > 0 || (color == SERIAL && moving == Moving::Both) {
                    self.ranges.push(ColourRun {
                        start,
                        end: start + groups,
                        moving,
                    });
                }
                start += groups;
            }
            #[cfg(feature = "parallel")]
            {
                let runs = &self.ranges[colour_runs..];
                if color == SERIAL {
                    self.blocks.add_stage(runs, true);
                } else {
                    let zone_starts = |moving: Moving| {
                        let first = zone_index(color, moving, 0, zone_count);
                        &self.zone_counts[first..first + zone_count]
                    };
                    pieces_by_zone(runs, zone_starts, &mut self.pieces);
                    self.blocks.add_stage(&self.pieces, false);
                }
            }
        }
        self.groups = start as usize;
        #[cfg(feature = "parallel")]
        self.blocks.finish();

        self.slot.clear();
        for &(color, moving, zone) in &self.color {
            let next = &mut self.zone_counts
                [zone_index(color as usize, moving, zone as usize, zone_count)];
            let k = *next;
            *next += 1;
            let (color, moving) = (color as usize, moving as usize);
            let first = first_group[color][moving];
            let slot = if color == SERIAL {
                (first + k) * LANES as u32
            } else {
                first * LANES as u32 + k
            };
            self.slot.push(slot);
        }
        // What this call used, cleared for the next.
        for color in (0..colours_used).chain([SERIAL]) {
            counts[color] = [0; 3];
        }
        let per_colour = 3 * zone_count;
        self.zone_counts[..colours_used * per_colour].fill(0);
        self.zone_counts[SERIAL * per_colour..].fill(0);
        self.counts = counts;
        self.first_group = first_group;
    }

    /// The colour of an overflowing constraint between `sides` (each a body
    /// and whether it moves): the level after its moving bodies' last, or
    /// `SERIAL` past the last level, after which their later ones stay serial too.
    fn overflow_colour(&mut self, sides: [(u32, bool); 2], bodies: usize) -> usize {
        #[cfg(test)]
        if self.serial_overflow {
            return SERIAL;
        }
        if self.next_level.is_empty() {
            self.next_level.resize(bodies, 0);
        }
        let moving = sides.into_iter().filter(|&(_, moves)| moves);
        let level = moving
            .clone()
            .map(|(i, _)| self.next_level[i as usize])
            .max();
        let level = level.unwrap_or(0) as usize;
        let next = (level + 1).min(LEVELS) as u16;
        for (i, _) in moving {
            self.next_level[i as usize] = next;
        }
        COLORS + level.min(LEVELS)
    }

    /// Tests only: every run (and block piece) as if both sides moved.
    #[cfg(test)]
    pub fn treat_every_side_as_moving(&mut self) {
        self.ranges.iter_mut().for_each(|r| r.moving = Moving::Both);
        #[cfg(feature = "parallel")]
        self.blocks
            .pieces
            .iter_mut()
            .for_each(|p| p.moving = Moving::Both);
    }
}

#[cfg(test)]
#[path = "coloring_tests.rs"]
mod tests;
