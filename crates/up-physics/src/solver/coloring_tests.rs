//! The colouring's invariants: no two constraints of a colour or level move
//! one body, and every body meets its constraints in the given order.

use glam::Mat3;

use super::*;

fn moving() -> BodyState {
    BodyState {
        inv_mass: 1.0,
        inv_inertia: Mat3::IDENTITY,
        ..BodyState::STATIC
    }
}

/// The constraints of each colour (then each level, then the serial rest), as (a, b) pairs.
fn colours(coloring: &Coloring, pairs: &[(u32, u32)]) -> Vec<Vec<(u32, u32)>> {
    let mut by_colour = vec![Vec::new(); SERIAL + 1];
    for (&pair, &(colour, _, _)) in pairs.iter().zip(&coloring.color) {
        by_colour[colour as usize].push(pair);
    }
    by_colour
}

/// The run holding each constraint's group.
fn runs(coloring: &Coloring) -> Vec<ColourRun> {
    let run_of = |slot: u32| {
        let group = slot / LANES as u32;
        *coloring
            .ranges
            .iter()
            .find(|r| (r.start..r.end).contains(&group))
            .unwrap()
    };
    coloring.slot.iter().map(|&slot| run_of(slot)).collect()
}

#[test]
fn no_colour_moves_a_body_twice_and_the_room_is_shared() {
    // A chain 0-1-2-3, a star around 4, and everything against the static room (5).
    let mut states = vec![moving(); 5];
    states.push(BodyState::STATIC);
    let mut pairs: Vec<(u32, u32)> = (0..5).map(|i| (i, 5)).collect();
    pairs.extend([(0, 1), (1, 2), (2, 3), (4, 0), (4, 1), (4, 2), (4, 3)]);

    let mut coloring = Coloring::default();
    coloring.assign(pairs.iter().copied(), &states, &[]);

    // Every constraint has its own slot, inside the groups.
    let mut slots = coloring.slot.clone();
    slots.sort_unstable();
    slots.dedup();
    assert_eq!(slots.len(), pairs.len());
    assert!(slots
        .iter()
        .all(|&s| (s as usize) < coloring.groups * LANES));
    // The five room contacts share colour 0 (the room does not count):
    // two groups, the first full, in the given order.
    let room_run = ColourRun {
        start: 0,
        end: 2,
        moving: Moving::A,
    };
    assert_eq!(coloring.ranges[0], room_run);
    assert_eq!(&coloring.slot[..5], &[0, 1, 2, 3, 4]);
    let by_colour = colours(&coloring, &pairs);
    for colour in &by_colour[..by_colour.len() - 1] {
        let mut bodies: Vec<u32> = colour
            .iter()
            .flat_map(|&(a, b)| [a, b])
            .filter(|&i| i != 5)
            .collect();
        let n = bodies.len();
        bodies.sort_unstable();
        bodies.dedup();
        assert_eq!(bodies.len(), n, "a body moved twice in {colour:?}");
    }
    // Nothing overflowed.
    assert!(by_colour.last().unwrap().is_empty());
}

/// A star of `COLORS + extra` constraints around body `hub` (its
/// spokes `first..`); returns the pairs.
fn star(hub: u32, first: u32, extra: usize) -> Vec<(u32, u32)> {
    (first..first + (COLORS + extra) as u32)
        .map(|i| (hub, i))
        .collect()
}

/// The levels of the overflow's constraints, in the given order.
fn levels(coloring: &Coloring) -> Vec<usize> {
    let over = coloring
        .color
        .iter()
        .filter(|&&(c, _, _)| c as usize >= COLORS);
    over.map(|&(c, _, _)| c as usize - COLORS).collect()
}

#[test]
fn overflowing_constraints_take_levels_in_their_bodies_order() {
    // Two stars: 5 and 3 constraints past the colours, each sharing its hub.
    let mut states = vec![moving(); 200];
    states.push(BodyState::STATIC);
    let mut pairs = star(0, 1, 5);
    pairs.extend(star(100, 101, 3));
    let mut coloring = Coloring::default();
    coloring.assign(pairs.iter().copied(), &states, &[]);
    assert_eq!(levels(&coloring), vec![0, 1, 2, 3, 4, 0, 1, 2]);
    // The levels come after the colours, in order, then the empty serial run.
    let runs = &coloring.ranges[COLORS..];
    let sizes: Vec<u32> = runs.iter().map(|r| r.end - r.start).collect();
    assert_eq!(sizes, vec![1, 1, 1, 1, 1, 0]);
    // The two stars' constraints of a level share a group.
    let slot = |i: usize| coloring.slot[i];
    for (k, level) in [(64, 0), (65, 1), (66, 2)] {
        let group = runs[level].start * LANES as u32;
        assert_eq!((slot(k), slot(k + 64 + 5)), (group, group + 1));
    }
    // Each body meets its overflowing constraints in the given order.
    let mut last_level = vec![None; states.len()];
    for (&(a, b), &(colour, _, _)) in pairs.iter().zip(&coloring.color) {
        if (colour as usize) < COLORS {
            continue;
        }
        for body in [a as usize, b as usize] {
            assert!(last_level[body] < Some(colour), "body {body}");
            last_level[body] = Some(colour);
        }
    }
}

#[test]
fn constraints_past_the_last_level_run_serially_one_a_group() {
    let spokes = COLORS + LEVELS + 3;
    let mut states = vec![moving(); spokes + 3];
    states.push(BodyState::STATIC);
    let mut pairs = star(0, 1, LEVELS + 3);
    // Between the hub, whose later constraints must stay serial, and a fresh body.
    pairs.push((spokes as u32 + 1, 0));
    let mut coloring = Coloring::default();
    coloring.assign(pairs.iter().copied(), &states, &[]);
    let serial = coloring.ranges.last().unwrap();
    assert_eq!(coloring.ranges.len(), SERIAL + 1);
    assert_eq!(serial.end - serial.start, 4);
    assert_eq!(serial.moving, Moving::Both);
    // Each alone in lane 0 of its group.
    let lanes: Vec<u32> = coloring.slot[COLORS + LEVELS..]
        .iter()
        .map(|s| s % LANES as u32)
        .collect();
    assert_eq!(lanes, vec![0; 4]);
}

/// Each colour's runs are cut into equal blocks of up to `BLOCK_GROUPS`
/// groups (a block may span runs), in order; the overflow stays whole;
/// stages of one block in a row become one block; empty colours add nothing.
#[cfg(feature = "parallel")]
#[test]
fn colours_are_cut_into_blocks_and_lone_blocks_join() {
    let run = |start, end, moving| ColourRun { start, end, moving };
    let mut blocks = ColourBlocks::default();
    blocks.add_stage(
        &[run(0, 150, Moving::Both), run(150, 160, Moving::A)],
        false,
    );
    blocks.add_stage(&[run(160, 170, Moving::Both)], false);
    blocks.add_stage(&[run(170, 175, Moving::B)], false);
    blocks.add_stage(&[run(175, 175, Moving::Both)], false);
    blocks.add_stage(&[run(175, 300, Moving::Both)], true); // the serial rest: whole
    blocks.add_stage(&[run(300, 400, Moving::Both)], false);

    let spans: Vec<Vec<(u32, u32, Moving)>> = (0..blocks.stage_first.len())
        .map(|k| {
            let pieces = blocks.block(k).iter();
            pieces.map(|p| (p.start, p.end, p.moving)).collect()
        })
        .collect();
    assert_eq!(
        spans,
        vec![
            vec![(0, 53, Moving::Both)],
            vec![(53, 106, Moving::Both)],
            vec![(106, 150, Moving::Both), (150, 160, Moving::A)],
            // Three one-block stages (the empty colour adds none), one block.
            vec![
                (160, 170, Moving::Both),
                (170, 175, Moving::B),
                (175, 300, Moving::Both),
            ],
            vec![(300, 350, Moving::Both)],
            vec![(350, 400, Moving::Both)],
        ]
    );
    assert_eq!(blocks.stage_first, vec![0, 0, 0, 3, 4, 4]);
}

/// Cut for two threads, a stage's blocks come in a multiple of two, of
/// equal size, so that each thread's share is half the stage; a stage with
/// fewer than `MIN_THREAD_GROUPS` groups a thread stays one block.
#[cfg(feature = "parallel")]
#[test]
fn blocks_share_a_stage_evenly_among_the_threads() {
    let run = |start, end| ColourRun {
        start,
        end,
        moving: Moving::Both,
    };
    let mut blocks = ColourBlocks {
        threads: 2,
        ..ColourBlocks::default()
    };
    blocks.add_stage(&[run(0, 70)], false);
    blocks.add_stage(&[run(70, 70 + 2 * MIN_THREAD_GROUPS - 1)], false);
    let next = 70 + 2 * MIN_THREAD_GROUPS - 1;
    blocks.add_stage(&[run(next, next + 200)], false);
    let sizes: Vec<u32> = (0..blocks.stage_first.len())
        .map(|k| blocks.block(k).iter().map(|p| p.end - p.start).sum())
        .collect();
    assert_eq!(
        sizes,
        vec![35, 35, 2 * MIN_THREAD_GROUPS - 1, 50, 50, 50, 50]
    );
    assert_eq!(blocks.stage_first, vec![0, 0, 2, 3, 3, 3, 3]);
}

/// The blocks of a real colouring hold every group once, in the runs' order.
#[cfg(feature = "parallel")]
#[test]
fn the_blocks_hold_every_group_in_order() {
    // A crowd of 400 bodies, each touching the room and its next 12.
    let mut states = vec![moving(); 400];
    states.push(BodyState::STATIC);
    let mut pairs: Vec<(u32, u32)> = (0..400).map(|i| (i, 400)).collect();
    pairs.extend((0..400u32).flat_map(|i| (1..=12).map(move |d| (i, (i + d) % 400))));
    let mut coloring = Coloring::default();
    coloring.assign(pairs.iter().copied(), &states, &[]);
    let blocks = &coloring.blocks;
    let stage_first = &blocks.stage_first;
    assert!(
        stage_first.windows(2).any(|w| w[0] == w[1]),
        "a stage of several blocks"
    );
    let mut next = 0;
    for k in 0..stage_first.len() {
        // What `run_in_stages` needs: k in its stage, which starts at its first block.
        let first = stage_first[k] as usize;
        assert!(first <= k && stage_first[first] as usize == first);
        assert!(k == 0 || stage_first[k - 1] <= stage_first[k]);
        let pieces = blocks.block(k);
        let groups: u32 = pieces.iter().map(|p| p.end - p.start).sum();
        // A block of a stage of several holds at most `BLOCK_GROUPS`.
        let alone = stage_first.get(k + 1) != Some(&(first as u32)) && first == k;
        assert!(
            alone || groups <= BLOCK_GROUPS,
            "block {k}: {groups} groups"
        );
        for piece in pieces {
            assert_eq!(piece.start, next);
            next = piece.end;
        }
    }
    assert_eq!(next as usize, coloring.groups);
}

/// Within a colour, the constraints against a fixed body (the room, a
/// sleeper) take groups of their own, by the side that moves, in the
/// given order within each; the runs say which side that is.
#[test]
fn constraints_against_fixed_bodies_get_groups_of_their_own() {
    // Bodies 0-3 move, 4 sleeps, 5 is the room.
    let mut states = vec![moving(); 4];
    let mut sleeper = BodyState::STATIC;
    sleeper.q = glam::Quat::from_rotation_z(0.3);
    states.extend([sleeper, BodyState::STATIC]);
    let pairs = [(0, 5), (4, 1), (2, 3), (1, 5), (3, 5), (4, 0)];
    let mut coloring = Coloring::default();
    coloring.assign(pairs.iter().copied(), &states, &[]);

    let run = |start, end, moving| ColourRun { start, end, moving };
    // Colour 0: (2, 3) between moving bodies, then (0, 5) against the
    // room, then (4, 1) against the sleeper; colour 1: (1, 5) and (3, 5)
    // in one group, then (4, 0); the overflow, empty.
    assert_eq!(
        coloring.ranges,
        vec![
            run(0, 1, Moving::Both),
            run(1, 2, Moving::A),
            run(2, 3, Moving::B),
            run(3, 4, Moving::A),
            run(4, 5, Moving::B),
            run(5, 5, Moving::Both),
        ]
    );
    assert_eq!(coloring.slot, vec![4, 8, 0, 12, 13, 16]);
    for ((a, b), run) in pairs.iter().zip(runs(&coloring)) {
        let (a, b) = (&states[*a as usize], &states[*b as usize]);
        assert_eq!(run.moving.fixes(0), a.is_fixed(), "{run:?}");
        assert_eq!(run.moving.fixes(1), b.is_fixed(), "{run:?}");
    }
}

/// With zones, each constraint keeps its colour and its run, but a run's
/// constraints come zone by zone; on several threads each colour's blocks
/// follow the zones across its runs, so that a share of the blocks is a
/// part of the room whichever sides move.
#[test]
fn zones_order_each_run_and_keep_every_colour() {
    // A crowd of 1,600 bodies, each touching its next 12, every third asleep
    // (so each colour has runs of both kinds of sides); zones by index.
    let n = 1600u32;
    let mut sleeper = BodyState::STATIC;
    sleeper.q = glam::Quat::from_rotation_z(0.3);
    let mut states: Vec<BodyState> = (0..n)
        .map(|i| if i % 3 == 0 { sleeper } else { moving() })
        .collect();
    states.push(BodyState::STATIC);
    let pairs: Vec<(u32, u32)> = (0..n)
        .flat_map(|i| (1..=12).map(move |d| (i, (i + d) % n)))
        .filter(|&(a, b)| a % 3 != 0 || b % 3 != 0)
        .collect();
    let zones: Vec<u8> = (0..n)
        .map(|i| (i as usize * ZONES / n as usize) as u8)
        .collect();
    let mut plain = Coloring::default();
    plain.assign(pairs.iter().copied(), &states, &[]);
    let mut zoned = Coloring::default();
    zoned.assign(pairs.iter().copied(), &states, &zones);

    assert_eq!(colours(&plain, &pairs), colours(&zoned, &pairs));
    assert_eq!(plain.ranges, zoned.ranges);
    assert_eq!(runs(&plain), runs(&zoned));
    let zone_of_slot: std::collections::HashMap<u32, u8> = zoned
        .slot
        .iter()
        .zip(&pairs)
        .map(|(&slot, &(a, _))| (slot, zones[a as usize]))
        .collect();
    for run in &zoned.ranges {
        let slots = run.start * LANES as u32..run.end * LANES as u32;
        let in_order: Vec<u8> = slots
            .filter_map(|s| zone_of_slot.get(&s).copied())
            .collect();
        assert!(in_order.is_sorted(), "{run:?}: {in_order:?}");
    }
    #[cfg(feature = "parallel")]
    {
        let blocks = &zoned.blocks;
        let stage_first = &blocks.stage_first;
        let mut mixed_stages = 0;
        for (k, &first) in stage_first.iter().enumerate() {
            // Each stage of several blocks once, from its first (a lone block may
            // hold several colours, each in zone order).
            let several = stage_first.get(k + 1) == Some(&first);
            if first as usize != k || !several {
                continue;
            }
            let stage = (k..stage_first.len()).take_while(|&j| stage_first[j] == first);
            let pieces: Vec<ColourRun> = stage.flat_map(|j| blocks.block(j).to_vec()).collect();
            // The zone of each piece's first group (the zone of its last lane
            // that holds a constraint), along the stage; but for pieces of one
            // group (a run's last group, partly filled, goes with the last zone).
            let piece_zones: Vec<u8> = pieces
                .iter()
                .filter(|p| p.end - p.start > 1)
                .filter_map(|p| {
                    let lanes = p.start * LANES as u32..(p.start + 1) * LANES as u32;
                    lanes.rev().find_map(|s| zone_of_slot.get(&s).copied())
                })
                .collect();
            assert!(
                piece_zones.is_sorted(),
                "stage at block {k}: {piece_zones:?}"
            );
            if pieces
                .windows(2)
                .filter(|w| w[0].moving != w[1].moving)
                .count()
                > 1
            {
                mixed_stages += 1;
            }
        }
        assert!(mixed_stages > 0, "a stage whose zones interleave two runs");
    }
}
