//! The step's cost with the ribbons' contacts on and off, alternated in one
//! process: `cargo run -p up-scene --release --example ribbon_touch_cost --
//! SCENE COUNT STEPS REPEATS [on|off]` (COUNT 0: the scene's own balloon
//! count; SCENE `bench`: the benchmark scene of COUNT balloons, seed 1,
//! each on the default scene's ribbon; `on` or `off`: only those runs, as
//! for a profile of one).
//! Prints each run's mean and median step, ms, and the ratio of the means.

use std::time::Instant;

use up_scene::build::build_world;
use up_scene::scene::Scene;

fn run(scene: &Scene, contacts: bool, steps: usize) -> (f64, f64, f64) {
    let mut world = build_world(scene).unwrap_or_else(|e| panic!("{e}")).world;
    world.set_ribbon_contacts(contacts);
    let mut pairs = 0;
    let mut times: Vec<f64> = (0..steps)
        .map(|_| {
            let start = Instant::now();
            world.step();
            pairs += world.ribbon_contact_pairs();
            start.elapsed().as_secs_f64() * 1e3
        })
        .collect();
    let mean = times.iter().sum::<f64>() / steps as f64;
    times.sort_by(f64::total_cmp);
    (mean, times[steps / 2], pairs as f64 / steps as f64)
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let path = args.first().map_or("assets/scenes/bouquet.toml", |s| s);
    let arg = |k: usize, default: usize| args.get(k).map_or(default, |s| s.parse().unwrap());
    let (count, steps, repeats) = (arg(1, 0), arg(2, 300), arg(3, 3));
    let runs: &[bool] = match args.get(4).map(String::as_str) {
        Some("on") => &[true],
        Some("off") => &[false],
        _ => &[false, true],
    };
    let mut scene = if path == "bench" {
        let ribbon = Scene::from_path("assets/scenes/default.toml")
            .unwrap()
            .balloons[0]
            .ribbon
            .clone();
        let (mut scene, _) = up_scene::build::bench_scene::bench_scene(count as u64, 1).unwrap();
        for group in &mut scene.balloons {
            group.ribbon = ribbon.clone();
        }
        scene
    } else {
        Scene::from_path(path).unwrap_or_else(|e| panic!("{e}"))
    };
    if count > 0 && path != "bench" {
        scene.balloons[0].count = count as u64;
    }
    let (mut on, mut off) = (0.0, 0.0);
    for _ in 0..repeats {
        for &contacts in runs {
            let (mean, median, pairs) = run(&scene, contacts, steps);
            println!(
                "contacts {contacts:5}: mean {mean:.3} ms, median {median:.3} ms, {pairs:.0} pairs a step"
            );
            if contacts {
                on += mean;
            } else {
                off += mean;
            }
        }
    }
    if runs.len() == 2 {
        println!("on / off, by the means: {:.3}", on / off);
    }
}
