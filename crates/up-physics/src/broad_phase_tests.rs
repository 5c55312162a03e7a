//! The broadphase's tests: its pairs against every pair's test (in a table
//! of a bucket a cell and in a hashed one), their order, the woken bodies'
//! pairs, a table kept over many steps, and a table rebuilt in tasks.

use super::*;

use crate::hash::uniform as random;

/// `n` centres at random in a cube `width` wide round the origin (cells on
/// both sides of zero); with `strewn_every`, every so many of them a
/// million times farther out, where the cell coordinates are clamped.
fn cloud(
    rnd: &mut impl FnMut() -> f32,
    n: usize,
    width: f32,
    strewn_every: Option<usize>,
) -> Vec<Vec3> {
    (0..n)
        .map(|i| {
            let c = (Vec3::new(rnd(), rnd(), rnd()) - 0.5) * width;
            match strewn_every {
                Some(every) if i % every == 0 => c * 1.0e6,
                _ => c,
            }
        })
        .collect()
}

/// Brute-force reference on random clouds: the grid finds exactly the
/// overlapping pairs, whether its table has a bucket a cell (a cloud in a
/// room) or hashes them (a few bodies strewn far out).
#[test]
fn grid_pairs_equal_all_pairs_reference() {
    let mut rnd = random(12345);
    for round in 0..40 {
        let n = 50 + (round / 2) * 20;
        let strewn = round % 2 == 0;
        let center = cloud(&mut rnd, n, 3.0, strewn.then_some(23));
        // A few large (fast) bodies among ordinary ones.
        let radius: Vec<f32> = (0..n)
            .map(|i| {
                if i % 17 == 0 {
                    0.2 + rnd()
                } else {
                    0.05 + 0.15 * rnd()
                }
            })
            .collect();
        let awake: Vec<bool> = (0..n).map(|i| i % 5 != 0).collect();
        let mut bp = BroadPhase::default();
        bp.update(&center, &radius, &awake, 0.2);
        assert_eq!(bp.buckets.dense.is_none(), strewn, "round {round}");
        let mut got = bp.pairs.clone();
        got.sort_unstable();
        let mut want = Vec::new();
        for a in 0..n {
            for b in a + 1..n {
                consider(&mut want, a as u32, b as u32, &center, &radius, &awake);
            }
        }
        want.sort_unstable();
        assert_eq!(got, want, "round {round}");
    }
}

/// The order the step's determinism rests on, whatever cells the lookups
/// skip: by awake body, then by the cell of the other one (x, then y,
/// then z, among the 27 around it), then by the other body. Spheres as
/// wide as the cells allow, and just touching ones, so that the pairs
/// reach into the skipped cells' edges.
#[test]
fn grid_pairs_come_by_body_then_cell_then_body() {
    let mut rnd = random(4242);
    let cell_radius = 0.2;
    for round in 0..10 {
        let n = 200 + round * 40;
        let center: Vec<Vec3> = (0..n)
            .map(|_| Vec3::new(rnd(), rnd(), rnd()) * 2.0 - 0.3)
            .collect();
        let mut radius: Vec<f32> = (0..n).map(|_| 0.1 + 0.1 * rnd()).collect();
        // A few pairs exactly at touching distance.
        for k in (0..n - 1).step_by(7) {
            radius[k + 1] = (center[k].distance(center[k + 1]) - radius[k]).clamp(0.0, 0.2);
        }
        let awake: Vec<bool> = (0..n).map(|i| i % 4 != 0).collect();
        let mut bp = BroadPhase::default();
        bp.update(&center, &radius, &awake, cell_radius);

        let cell = |i: usize| cell_coords(center[i], 0.5 / cell_radius);
        let mut want = Vec::new();
        for i in (0..n).filter(|&i| awake[i]) {
            let mut others: Vec<([i32; 3], usize)> = (0..n)
                .filter(|&j| j != i && (j > i || !awake[j]))
                .map(|j| {
                    let offset: [i32; 3] = std::array::from_fn(|k| cell(j)[k] - cell(i)[k]);
                    (offset, j)
                })
                .filter(|(offset, _)| offset.iter().all(|d| d.abs() <= 1))
                .collect();
            others.sort_unstable();
            for (_, j) in others {
                consider(&mut want, i as u32, j as u32, &center, &radius, &awake);
            }
        }
        assert_eq!(bp.pairs, want, "round {round}");
    }
}

/// A table kept over many steps (a few bodies moving, some across
/// cells, some falling asleep or waking, now and then one large) gives
/// the pairs, in the same order, that a table built afresh gives.
#[test]
fn a_kept_table_gives_what_a_fresh_one_gives() {
    let mut rnd = random(2024);
    let n = 300;
    let mut center: Vec<Vec3> = (0..n)
        .map(|_| Vec3::new(rnd() * 3.0, rnd() * 3.0, rnd() * 3.0))
        .collect();
    let mut radius: Vec<f32> = (0..n).map(|_| 0.05 + 0.15 * rnd()).collect();
    let mut awake: Vec<bool> = (0..n).map(|_| rnd() < 0.1).collect();
    let mut kept = BroadPhase::default();
    let mut refreshed = 0;
    for step in 0..400 {
        for i in 0..n {
            if awake[i] {
                // Mostly a creep; now and then a jump across cells.
                let size = if rnd() < 0.02 { 0.3 } else { 0.002 };
                center[i] += (Vec3::new(rnd(), rnd(), rnd()) - 0.5) * size;
                radius[i] = (radius[i] + 0.001 * (rnd() - 0.5)).clamp(0.05, 0.2);
            }
            if rnd() < 0.002 {
                awake[i] = !awake[i];
            }
        }
        let large = (step % 97 == 5).then(|| (step * 7) % n);
        if let Some(l) = large {
            radius[l] = 0.6;
        }
        if matches!(
            kept.clone().refresh(&center, &radius, &awake, 0.2),
            Refreshed::Kept
        ) {
            refreshed += 1;
        }
        kept.update(&center, &radius, &awake, 0.2);
        let mut fresh = BroadPhase::default();
        fresh.update(&center, &radius, &awake, 0.2);
        assert_eq!(kept.pairs, fresh.pairs, "step {step}");
        if let Some(l) = large {
            radius[l] = 0.1;
        }
    }
    assert!(refreshed > 100, "the table was rebuilt nearly every step");
}

/// A crowd drifting together, a few of it across cells at every step (so
/// the kept table is rebuilt without a refresh tried, `REFRESH_SKIPS`),
/// then coming to rest: the kept table gives the pairs a fresh one gives,
/// and refreshes again once the crowd rests.
#[test]
fn a_kept_table_of_a_drifting_crowd_gives_what_a_fresh_one_gives() {
    let mut rnd = random(99);
    let n = 400;
    let mut center: Vec<Vec3> = (0..n)
        .map(|_| Vec3::new(rnd() * 4.0, rnd() * 4.0, rnd() * 4.0))
        .collect();
    let radius: Vec<f32> = (0..n).map(|_| 0.05 + 0.15 * rnd()).collect();
    let awake = vec![true; n];
    let mut kept = BroadPhase::default();
    let (mut skipped, mut refreshed_at_rest) = (0, 0);
    for step in 0..120 {
        if step < 80 {
            for c in &mut center {
                *c += Vec3::new(0.0, 0.017, 0.0) + (Vec3::new(rnd(), rnd(), rnd()) - 0.5) * 0.004;
            }
        }
        if kept.skip_refresh > 0 {
            skipped += 1;
        } else if step >= 90
            && matches!(
                kept.clone().refresh(&center, &radius, &awake, 0.2),
                Refreshed::Kept
            )
        {
            refreshed_at_rest += 1;
        }
        kept.update(&center, &radius, &awake, 0.2);
        let mut fresh = BroadPhase::default();
        fresh.update(&center, &radius, &awake, 0.2);
        assert_eq!(kept.pairs, fresh.pairs, "step {step}");
    }
    assert!(
        skipped > 50,
        "refreshes skipped in {skipped} steps of the drift"
    );
    assert_eq!(refreshed_at_rest, 30, "the table at rest was rebuilt");
}

#[test]
fn woken_pairs_complete_the_update_as_a_new_update_would() {
    let mut rnd = random(777);
    for round in 0..20 {
        let n = 60 + round * 25;
        let center: Vec<Vec3> = (0..n)
            .map(|_| Vec3::new(rnd() * 3.0, rnd() * 3.0, rnd() * 3.0))
            .collect();
        let radius: Vec<f32> = (0..n).map(|_| 0.05 + 0.15 * rnd()).collect();
        let was_awake: Vec<bool> = (0..n).map(|_| rnd() < 0.3).collect();
        // Some sleepers wake, neighbours of each other among them.
        let awake: Vec<bool> = was_awake.iter().map(|&w| w || rnd() < 0.4).collect();
        let mut bp = BroadPhase::default();
        bp.update(&center, &radius, &was_awake, 0.2);
        assert!(bp.add_woken_pairs(&center, &radius, &was_awake, &awake));
        let mut got = bp.pairs.clone();
        let count = got.len();
        got.sort_unstable();
        got.dedup();
        assert_eq!(got.len(), count, "a pair found twice, round {round}");
        bp.update(&center, &radius, &awake, 0.2);
        let mut want = bp.pairs.clone();
        want.sort_unstable();
        assert_eq!(got, want, "round {round}");
    }
}

#[test]
fn woken_pairs_defer_to_a_full_update_when_large_bodies_are_about() {
    let center = vec![Vec3::ZERO, Vec3::X * 0.3];
    let radius = vec![1.0, 0.1];
    let mut bp = BroadPhase::default();
    bp.update(&center, &radius, &[false, false], 0.2);
    assert!(!bp.add_woken_pairs(&center, &radius, &[false, false], &[true, false]));
}

/// A table rebuilt in tasks is the one built on one thread, entry for
/// entry: thousands of bodies (several tasks' worth), large ones and a NaN
/// radius among them, in a table of a bucket a cell and in a hashed one.
#[cfg(feature = "parallel")]
#[test]
fn a_table_rebuilt_in_tasks_is_the_one_built_on_one_thread() {
    let mut rnd = random(777);
    for strewn in [false, true] {
        let n = 5 * BODY_CHUNK + 37;
        let center = cloud(&mut rnd, n, 6.0, strewn.then_some(97));
        let radius: Vec<f32> = (0..n)
            .map(|i| match i % 211 {
                0 => 0.3 + rnd(),
                5 => f32::NAN,
                _ => 0.05 + 0.15 * rnd(),
            })
            .collect();
        let awake: Vec<bool> = (0..n).map(|i| i % 7 != 0).collect();
        let built = |threads: usize| {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            pool.install(|| {
                let mut table = BroadPhase::default();
                table.rebuild(&center, &radius, &awake, 0.2);
                table
            })
        };
        let (one, three) = (built(1), built(3));
        let entries = |table: &BroadPhase| -> Vec<_> {
            let bits = |v: Vec3| v.to_array().map(f32::to_bits);
            let entry =
                |e: &GridItem| (bits(e.center), e.radius.to_bits(), e.cell, e.body, e.awake);
            table.items.iter().map(entry).collect()
        };
        assert_eq!(one.buckets.dense.is_none(), strewn);
        assert_eq!(one.buckets.dense, three.buckets.dense);
        assert_eq!(one.buckets.mask, three.buckets.mask);
        assert_eq!(entries(&one), entries(&three));
        assert_eq!(one.start, three.start);
        assert_eq!(one.slot_of, three.slot_of);
        assert_eq!(one.cell_of, three.cell_of);
        assert!(!one.large.is_empty());
        assert_eq!(one.large, three.large);
        let item_radius = |table: &BroadPhase| table.scale.item_radius.to_bits();
        assert_eq!(item_radius(&one), item_radius(&three));
    }
}
