//! The contacts written into their groups by tasks (`parallel::scatter_lanes`,
//! each lane through `set_lane_shared`) must leave the groups as one thread
//! writing each into its slot of empty groups (`set_lane`) does, bit for bit.

use glam::Vec3;

use super::contact_constraint::{
    set_lane, ContactGroup, GroupAnchors, GroupRecords, PreparedContact,
};
use super::lanes::LANES;
use super::parallel::{fill_groups, scatter_lanes};
use crate::contact::ContactFeature;
use crate::hash::uniform;

/// `count` contacts whose every field differs from every other's.
fn contacts(count: usize, seed: u64) -> Vec<PreparedContact> {
    let mut random = uniform(seed);
    let mut v = || Vec3::new(random(), random(), random());
    (0..count)
        .map(|i| PreparedContact {
            a: i as u32,
            b: 7 * i as u32 + 1,
            normal: v(),
            tangent: [v(), v()],
            r_a: v(),
            r_b: v(),
            radius_a: v().x,
            radius_b: v().y,
            center_offset: v(),
            adjusted_separation: v().z,
            normal_impulse: v().x,
            tangent_impulse: [v().y, v().z],
            feature: ContactFeature {
                leaf_a: 3 * i as u32,
                part_b: 5 * i as u32,
            },
        })
        .collect()
}

/// Distinct slots for `count` constraints in `groups` groups, shuffled, so
/// that neighbouring contacts land in groups far apart and runs of them
/// share groups.
fn slots(count: usize, groups: usize, seed: u64) -> Vec<u32> {
    let mut random = uniform(seed);
    let mut all: Vec<u32> = (0..(groups * LANES) as u32).collect();
    for i in (1..all.len()).rev() {
        let j = ((random() * (i + 1) as f32) as usize).min(i);
        all.swap(i, j);
    }
    all.truncate(count);
    all
}

type Groups = (Vec<ContactGroup>, Vec<GroupAnchors>, Vec<GroupRecords>);

fn empty_groups(n: usize, room: u32) -> Groups {
    (
        vec![ContactGroup::empty(room); n],
        vec![GroupAnchors::default(); n],
        vec![GroupRecords::default(); n],
    )
}

#[test]
fn contacts_scattered_by_tasks_fill_their_groups_as_one_thread_does() {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(4)
        .build()
        .unwrap();
    let (count, n, room) = (20_000, 5_200, 99_999);
    for seed in 1..=3 {
        let prepared = contacts(count, seed);
        let slots = slots(count, n, seed + 10);
        let mut serial = empty_groups(n, room);
        for (c, &slot) in prepared.iter().zip(&slots) {
            let (g, lane) = (slot as usize / LANES, slot as usize % LANES);
            let parts = (&mut serial.0[g], &mut serial.1[g], &mut serial.2[g]);
            set_lane(parts, lane, c);
        }
        // Groups holding another step's contacts, emptied first as the
        // solver does.
        let mut tasks = (
            vec![ContactGroup::default(); n],
            vec![GroupAnchors::default(); n],
            vec![GroupRecords::default(); n],
        );
        let old = contacts(n * LANES, seed + 20);
        for (k, c) in old.iter().enumerate() {
            let g = k / LANES;
            set_lane(
                (&mut tasks.0[g], &mut tasks.1[g], &mut tasks.2[g]),
                k % LANES,
                c,
            );
        }
        pool.install(|| {
            let empty = (
                ContactGroup::empty(room),
                GroupAnchors::default(),
                GroupRecords::default(),
            );
            fill_groups((&mut tasks.0, &mut tasks.1, &mut tasks.2), |_, parts| {
                (*parts.0, *parts.1, *parts.2) = empty;
            });
            let parts = (&mut tasks.0[..], &mut tasks.1[..], &mut tasks.2[..]);
            // SAFETY: `slots` are distinct (a shuffle of distinct slots).
            unsafe { scatter_lanes(parts, &slots, &prepared) };
        });
        // Debug prints every field, each float exactly enough to tell it apart.
        assert_eq!(format!("{serial:?}"), format!("{tasks:?}"), "seed {seed}");
    }
}
