//! `up air`: the room's moving air (its fans, vents and draughts,
//! `up_physics::air`) at given points and time, so that anyone can check the
//! field a scene makes without running it.

use std::path::PathBuf;

use anyhow::{bail, Result};
use clap::Args;
use glam::Vec3;
use serde::Serialize;
use up_scene::build::air::{air_flow, check_air_in};
use up_scene::build::build_room;
use up_scene::scene::Scene;

#[derive(Args, Debug)]
pub struct AirArgs {
    /// Scene file (.toml or .json).
    pub scene: PathBuf,
    /// A point, m, world frame (origin at the centre of the floor, Y up):
    /// X,Y,Z; give --at once for each point. Inside the room's bounds.
    #[arg(
        long = "at",
        value_name = "X,Y,Z",
        required = true,
        allow_hyphen_values = true,
        value_parser = parse_point
    )]
    pub at: Vec<[f32; 3]>,
    /// Simulated time, s: where sweeping fans point and which sources are
    /// on then. Finite, ≥ 0.
    #[arg(
        long = "t",
        value_name = "S",
        default_value_t = 0.0,
        allow_negative_numbers = true
    )]
    pub t: f64,
    /// End with one JSON object on the last line of standard output.
    #[arg(long)]
    pub json: bool,
}

/// Most points one command takes.
const MAX_POINTS: usize = 100_000;

/// The last line of `up air --json`.
#[derive(Debug, Serialize)]
struct AirJson {
    scene: String,
    t_s: f64,
    fans: usize,
    vents: usize,
    draughts: usize,
    points: Vec<AirPoint>,
}

/// The air at one point.
#[derive(Debug, Serialize)]
struct AirPoint {
    at_m: [f32; 3],
    velocity_m_s: [f32; 3],
    speed_m_s: f32,
}

/// `X,Y,Z`: three finite numbers, m.
fn parse_point(text: &str) -> Result<[f32; 3], String> {
    let parts: Vec<&str> = text.split(',').map(str::trim).collect();
    let numbers: Vec<f32> = parts
        .iter()
        .map(|p| p.parse::<f32>())
        .collect::<Result<_, _>>()
        .map_err(|_| format!("expected X,Y,Z, three numbers in m, found {text:?}"))?;
    match <[f32; 3]>::try_from(numbers.as_slice()) {
        Ok(p) if p.iter().all(|x| x.is_finite()) => Ok(p),
        Ok(_) => Err(format!("expected finite numbers, found {text:?}")),
        Err(_) => Err(format!(
            "expected X,Y,Z, three numbers in m, found {} in {text:?}",
            numbers.len()
        )),
    }
}

pub fn run(args: &AirArgs) -> Result<()> {
    if !(args.t.is_finite() && args.t >= 0.0) {
        bail!(
            "--t: expected a simulated time in s, finite and ≥ 0, found {}",
            args.t
        );
    }
    if args.at.len() > MAX_POINTS {
        bail!(
            "--at: expected at most {MAX_POINTS} points, found {}",
            args.at.len()
        );
    }
    let scene = Scene::from_path(&args.scene)?;
    let room = build_room(&scene)?;
    check_air_in(&scene, &room)?;
    let bounds = room.bounds();
    for p in &args.at {
        let point = Vec3::from_array(*p);
        if !bounds.contains_point(point) {
            bail!(
                "--at {}: expected a point inside the room's bounds, from {} to {} m",
                format_point(*p),
                bounds.min,
                bounds.max
            );
        }
    }
    let air = air_flow(&scene);
    let points: Vec<AirPoint> = args
        .at
        .iter()
        .map(|&at| {
            let u = air.velocity_at(Vec3::from_array(at), args.t);
            AirPoint {
                at_m: at,
                velocity_m_s: u.to_array(),
                speed_m_s: u.length(),
            }
        })
        .collect();
    let name = args.scene.display().to_string();
    let (fans, vents, draughts) = (scene.fans.len(), scene.vents.len(), scene.draughts.len());
    println!("up air: {name} at t = {} s: {}", args.t, sources(&scene));
    println!(
        "  {:>8} {:>8} {:>8}   {:>8} {:>8} {:>8}   {:>8}",
        "x m", "y m", "z m", "u_x m/s", "u_y m/s", "u_z m/s", "speed"
    );
    for p in &points {
        let [x, y, z] = p.at_m;
        let [ux, uy, uz] = p.velocity_m_s;
        println!(
            "  {x:>8.3} {y:>8.3} {z:>8.3}   {ux:>8.4} {uy:>8.4} {uz:>8.4}   {:>8.4}",
            p.speed_m_s
        );
    }
    if args.json {
        let json = AirJson {
            scene: name,
            t_s: args.t,
            fans,
            vents,
            draughts,
            points,
        };
        println!("{}", serde_json::to_string(&json)?);
    }
    Ok(())
}

fn format_point([x, y, z]: [f32; 3]) -> String {
    format!("{x},{y},{z}")
}

/// "1 fan, no vents, 3 draughts": a scene's sources of moving air.
pub fn sources(scene: &Scene) -> String {
    format!(
        "{}, {}, {}",
        count(scene.fans.len(), "fan", "fans"),
        count(scene.vents.len(), "vent", "vents"),
        count(scene.draughts.len(), "draught", "draughts")
    )
}

/// "1 fan", "no vents", "3 draughts".
fn count(n: usize, one: &str, many: &str) -> String {
    match n {
        0 => format!("no {many}"),
        1 => format!("1 {one}"),
        _ => format!("{n} {many}"),
    }
}
