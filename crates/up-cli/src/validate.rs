//! `up validate`: check a scene file (parse, ranges, and a full build, so
//! balloons that do not fit are caught) and print what it describes.

use std::path::PathBuf;

use anyhow::Result;
use clap::Args;
use up_scene::build::build_world;
use up_scene::scene::{CeilingKind, GasKind, JetSource, Scene};

use crate::summary::print_table;

#[derive(Args, Debug)]
pub struct ValidateArgs {
    /// Scene file (.toml or .json).
    pub scene: PathBuf,
}

pub fn run(args: &ValidateArgs) -> Result<()> {
    let scene = Scene::from_path(&args.scene)?;
    let built = build_world(&scene)?;
    let atmosphere = scene.air.atmosphere();
    let air_density = atmosphere.air_density();
    let gravity = glam::Vec3::from_array(scene.sim.gravity).length();

    let room = match (&scene.room.mesh, scene.room.ceiling) {
        (Some(mesh), _) => format!("mesh {mesh}"),
        (None, CeilingKind::Pyramid) => format!(
            "{} m × {} m, walls {} m, pyramid ceiling {} m above them",
            scene.room.width, scene.room.depth, scene.room.wall_height, scene.room.apex_height
        ),
        (None, CeilingKind::Flat) => format!(
            "{} m × {} m, walls {} m, flat ceiling",
            scene.room.width, scene.room.depth, scene.room.wall_height
        ),
    };
    let bounds = built.room.bounds();
    let mut rows = vec![
        ("room", room),
        ("room bounds", format!("{} to {} m", bounds.min, bounds.max)),
        (
            "air",
            format!(
                "{} °C, {} kPa: air {:.4} kg/m³, helium {:.4} kg/m³",
                scene.air.temperature_c,
                scene.air.pressure_kpa,
                air_density,
                atmosphere.helium_density()
            ),
        ),
        (
            "simulation",
            format!(
                "seed {}, dt {} s × {} substeps, {} s by default",
                scene.sim.seed, scene.sim.dt, scene.sim.substeps, scene.sim.duration_s
            ),
        ),
        (
            "balloons",
            format!(
                "{} in {} group(s)",
                scene.total_balloons(),
                scene.balloons.len()
            ),
        ),
    ];
    let groups: Vec<(String, String)> = scene
        .balloons
        .iter()
        .zip(&built.balloon_models)
        .enumerate()
        .map(|(i, (group, model))| {
            let shape = &model.shape;
            let lift = (air_density * shape.volume - shape.mass) * gravity;
            let gas = match group.gas {
                GasKind::Helium => "helium",
                GasKind::Air => "air",
            };
            let spawn = match &group.spawn {
                Some(b) => format!("in {:?} to {:?} m", b.min, b.max),
                None => "on the floor".to_string(),
            };
            let ribbon = match group.tied_ribbon() {
                Some(r) => {
                    let grams = r.length_m * r.mass_per_m_g;
                    let weight = if r.weight_g > 0.0 {
                        format!(", a {} g weight", r.weight_g)
                    } else {
                        String::new()
                    };
                    format!(
                        "; ribbon {} m of {} segments, {grams:.3} g, {}{weight}",
                        r.length_m, r.segments, r.color
                    )
                }
                None => String::new(),
            };
            let value = format!(
                "{} × {:.3} m {gas}, {:.2} g, net lift {:+.4} N, {} leaves, {}; colours {}{ribbon}",
                group.count,
                group.diameter(),
                shape.mass * 1000.0,
                lift,
                shape.tree.leaves().len(),
                spawn,
                group.colors.join(", "),
            );
            (format!("  group {i}"), value)
        })
        .collect();
    rows.extend(groups.iter().map(|(k, v)| (k.as_str(), v.clone())));
    let sources = air_rows(&scene);
    rows.extend(sources.iter().map(|(k, v)| (k.as_str(), v.clone())));
    let furniture: Vec<(String, String)> = scene
        .furniture
        .iter()
        .zip(&built.furniture)
        .enumerate()
        .map(|(i, (spec, piece))| {
            let size = spec
                .resolved_size()
                .map_or(String::new(), |[w, h, d]| format!(" {w} × {h} × {d} m"));
            let at = format!("at {:?}, turned {}°", spec.position, spec.yaw_deg);
            let count = piece.triangles.len();
            let value = format!("{}{size} {at}; {count} triangles", piece.label);
            (format!("furniture {i}"), value)
        })
        .collect();
    rows.extend(furniture.iter().map(|(k, v)| (k.as_str(), v.clone())));
    print_table(&format!("{}: valid", args.scene.display()), &rows);
    Ok(())
}

/// A row per fan, vent and draught, with its kind's defaults filled in;
/// none for still air.
fn air_rows(scene: &Scene) -> Vec<(String, String)> {
    let on = |intervals: &[[f64; 2]]| match intervals {
        [] => "always on".to_string(),
        _ => {
            let list: Vec<String> = intervals
                .iter()
                .map(|[a, b]| format!("{a}–{b} s"))
                .collect();
            format!("on {}", list.join(", "))
        }
    };
    let jets = scene.jets().map(|(at, source, spec)| {
        let jet = spec.resolved(source);
        let kind = match source {
            JetSource::Fan => "fan",
            JetSource::Vent => "vent",
        };
        let sweep = if spec.sweep_deg > 0.0 {
            format!(
                ", sweeping {}° every {} s",
                spec.sweep_deg, spec.sweep_period_s
            )
        } else {
            String::new()
        };
        let value = format!(
            "{kind} at {:?} m blowing {:?}, {} m across at {} m/s{sweep}, {}",
            jet.position,
            jet.direction,
            jet.diameter_m,
            jet.speed_m_s,
            on(&spec.on)
        );
        (format!("  {at}"), value)
    });
    let draughts = scene.draughts.iter().enumerate().map(|(i, d)| {
        let value = format!(
            "opening {:?} to {:?} m, air {:?} m/s through it, {}",
            d.min,
            d.max,
            d.velocity_m_s,
            on(&d.on)
        );
        (format!("  draughts[{i}]"), value)
    });
    let rows: Vec<(String, String)> = jets.chain(draughts).collect();
    if rows.is_empty() {
        return rows;
    }
    let title = (
        "moving air".to_string(),
        format!(
            "{} fan(s), {} vent(s), {} draught(s) (up air SCENE --at X,Y,Z prints it)",
            scene.fans.len(),
            scene.vents.len(),
            scene.draughts.len()
        ),
    );
    std::iter::once(title).chain(rows).collect()
}
