//! `up forecast`: runs a scene over hours as a time-lapse and says, per
//! balloon group, when its balloons leave the ceiling and when they are down
//! (`up_scene::float_census` defines ceiling, hovering and floor).

use std::path::PathBuf;
use std::time::Instant;

use anyhow::{bail, Context, Result};
use clap::Args;
use plotters::prelude::*;
use serde::Serialize;
use up_physics::{BodyId, World};
use up_scene::atomic_file::AtomicFile;
use up_scene::build::build_world;
use up_scene::scene::Scene;
use up_scene::{FloatCensus, FloatState, GroupCensus};

use crate::run::{advance_fully, check_hours, progress_bar};
use crate::scene_arg::SceneArgs;
use crate::summary::print_table;

#[derive(Args, Debug)]
pub struct ForecastArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Simulated hours to run, in (0, 2000]; a time-lapse with the physics of
    /// a stepped run (as `up run --hours`).
    #[arg(
        long,
        value_name = "H",
        default_value_t = 24.0,
        allow_negative_numbers = true
    )]
    pub hours: f64,
    /// Simulated minutes between looks at where the balloons are, in (0, 60];
    /// a time printed is that of the first look that saw it.
    #[arg(
        long,
        value_name = "M",
        default_value_t = 1.0,
        allow_negative_numbers = true
    )]
    pub sample_minutes: f64,
    /// End with one JSON object on the last line of standard output.
    #[arg(long)]
    pub json: bool,
    /// Draw the share of balloons at the ceiling, hovering and on the floor
    /// against time (all groups together) as SVG.
    #[arg(long, value_name = "FILE.svg")]
    pub plot: Option<PathBuf>,
}

/// Longest `--sample-minutes`.
const MAX_SAMPLE_MINUTES: f64 = 60.0;

/// The last line of `up forecast --json`.
#[derive(Debug, Serialize)]
struct ForecastJson {
    hours: f64,
    groups: Vec<GroupForecast>,
    /// Wall-clock time of the run, s.
    wall_s: f64,
    steps: u64,
    jumps: u64,
    /// The scene's sources of moving air, which blew through the run
    /// (each switched by its `on` intervals).
    air: AirSources,
}

/// How many of each source of moving air a scene has.
#[derive(Debug, Serialize)]
struct AirSources {
    fans: usize,
    vents: usize,
    draughts: usize,
}

/// What one group did, times in hours from the start of the run; null: not within it.
#[derive(Clone, Debug, Serialize)]
struct GroupForecast {
    group: usize,
    count: usize,
    /// As the scene spells it: "latex" or "foil".
    kind: String,
    /// "none" or "hi-float".
    treatment: String,
    leaves_ceiling_h: LeavesCeiling,
    on_floor_h: OnFloor,
    /// Mean of the gas's lift now over its lift at fill, at the end.
    mean_lift_fraction_end: f32,
    /// Balloons that reached the ceiling at some look.
    reached_ceiling: usize,
}

#[derive(Clone, Debug, Serialize)]
struct LeavesCeiling {
    first: Option<f64>,
    median: Option<f64>,
}

#[derive(Clone, Debug, Serialize)]
struct OnFloor {
    median: Option<f64>,
}

/// One balloon's history, in hours.
#[derive(Clone, Copy, Debug, Default)]
struct History {
    reached_ceiling: bool,
    /// When it last left the ceiling; cleared if it goes back up.
    left_ceiling: Option<f64>,
    /// When it last came onto the floor; cleared if it leaves it.
    on_floor: Option<f64>,
}

impl History {
    fn update(&mut self, state: FloatState, hours: f64) {
        match state {
            FloatState::Ceiling => {
                self.reached_ceiling = true;
                self.left_ceiling = None;
            }
            _ if self.reached_ceiling && self.left_ceiling.is_none() => {
                self.left_ceiling = Some(hours);
            }
            _ => {}
        }
        match state {
            FloatState::Floor => {
                self.on_floor.get_or_insert(hours);
            }
            _ => self.on_floor = None,
        }
    }
}

/// The share of all balloons in each state at one look.
#[derive(Clone, Copy, Debug)]
struct Shares {
    hours: f64,
    ceiling: f64,
    hovering: f64,
    floor: f64,
}

pub fn run(args: &ForecastArgs) -> Result<()> {
    let hours = check_hours(args.hours)?;
    let minutes = args.sample_minutes;
    if !(minutes.is_finite() && minutes > 0.0 && minutes <= MAX_SAMPLE_MINUTES) {
        bail!(
            "--sample-minutes: expected a number of minutes in (0, {MAX_SAMPLE_MINUTES}], found {minutes}"
        );
    }
    if let Some(path) = &args.plot {
        // Probe the directory now rather than after a long run.
        AtomicFile::create(path).context("--plot")?;
    }
    let scene = args.scene.load()?;
    let mut built = build_world(&scene)?;
    let labels = group_labels(&scene);
    let groups = built.group_bodies.clone();
    let world = &mut built.world;

    let sample_s = minutes * 60.0;
    let total_s = hours * 3600.0;
    let looks = (total_s / sample_s).ceil().max(1.0) as u64;
    let mut census = FloatCensus::new();
    let mut histories: Vec<Vec<History>> = groups
        .iter()
        .map(|bodies| vec![History::default(); bodies.len()])
        .collect();
    let mut shares = Vec::with_capacity(looks as usize + 1);
    let start = world.time();
    let look = |census: &mut FloatCensus,
                world: &World,
                histories: &mut [Vec<History>],
                shares: &mut Vec<Shares>|
     -> Vec<GroupCensus> {
        let counts = census.observe(world);
        let now_h = (world.time() - start) / 3600.0;
        for (bodies, history) in groups.iter().zip(histories.iter_mut()) {
            for (&id, h) in bodies.iter().zip(history.iter_mut()) {
                if let Some(state) = census.state(id) {
                    h.update(state, now_h);
                }
            }
        }
        shares.push(share_of(&counts, now_h));
        counts
    };

    let progress = progress_bar(looks, "samples");
    let started = Instant::now();
    let (mut steps, mut jumps) = (0u64, 0u64);
    let mut last = look(&mut census, world, &mut histories, &mut shares);
    for k in 1..=looks {
        let ask = if k == looks {
            total_s - sample_s * (looks - 1) as f64
        } else {
            sample_s
        };
        let (s, j) = advance_fully(world, ask);
        steps += s;
        jumps += j;
        last = look(&mut census, world, &mut histories, &mut shares);
        if let Some(bar) = &progress {
            bar.set_position(k);
        }
    }
    if let Some(bar) = progress {
        bar.finish_and_clear();
    }
    let wall_s = started.elapsed().as_secs_f64();

    let forecasts: Vec<GroupForecast> = labels
        .into_iter()
        .enumerate()
        .map(|(g, (kind, treatment))| {
            let history = histories.get(g).map_or(&[][..], Vec::as_slice);
            let end = last.get(g).copied().unwrap_or_default();
            forecast_group(g, kind, treatment, history, &end, groups.get(g), world)
        })
        .collect();

    let air = if scene.has_moving_air() {
        format!(
            "{} (as the scene switches them)",
            crate::air::sources(&scene)
        )
    } else {
        "still".to_string()
    };
    let run = RunFacts {
        scene: args.scene.name(),
        air,
        hours,
        wall_s,
        steps,
        jumps,
    };
    print_forecast(&run, &forecasts);
    if let Some(path) = &args.plot {
        let svg = plot_svg(&shares, hours)?;
        let mut file = AtomicFile::create(path).context("--plot")?;
        std::io::Write::write_all(&mut file, svg.as_bytes())
            .with_context(|| format!("--plot: cannot write {}", path.display()))?;
        file.commit().context("--plot")?;
    }
    if args.json {
        let json = ForecastJson {
            hours,
            groups: forecasts,
            wall_s,
            steps,
            jumps,
            air: AirSources {
                fans: scene.fans.len(),
                vents: scene.vents.len(),
                draughts: scene.draughts.len(),
            },
        };
        println!("{}", serde_json::to_string(&json)?);
    }
    Ok(())
}

/// Each group's kind and treatment as the scene file spells them (read
/// through its serialised form, so the names are the file's).
fn group_labels(scene: &Scene) -> Vec<(String, String)> {
    scene
        .balloons
        .iter()
        .map(|group| {
            let value = serde_json::to_value(group).unwrap_or_default();
            let text = |key: &str, default: &str| {
                value
                    .get(key)
                    .and_then(|v| v.as_str())
                    .unwrap_or(default)
                    .to_string()
            };
            (text("kind", "latex"), text("treatment", "none"))
        })
        .collect()
}

fn forecast_group(
    group: usize,
    kind: String,
    treatment: String,
    history: &[History],
    end: &GroupCensus,
    bodies: Option<&Vec<BodyId>>,
    world: &World,
) -> GroupForecast {
    let count = bodies.map_or(0, Vec::len);
    let left: Vec<f64> = history.iter().filter_map(|h| h.left_ceiling).collect();
    let floor: Vec<f64> = history.iter().filter_map(|h| h.on_floor).collect();
    let carries_gas = bodies.is_some_and(|b| b.iter().any(|&id| world.gas(id).is_some()));
    GroupForecast {
        group,
        count,
        kind,
        treatment,
        leaves_ceiling_h: LeavesCeiling {
            first: left.iter().copied().reduce(f64::min),
            median: half_way(left, count),
        },
        on_floor_h: OnFloor {
            median: half_way(floor, count),
        },
        mean_lift_fraction_end: if carries_gas {
            end.mean_lift_fraction
        } else {
            1.0
        },
        reached_ceiling: history.iter().filter(|h| h.reached_ceiling).count(),
    }
}

/// When half of `count` balloons had got there: the ⌈count/2⌉-th earliest
/// of `times`; None if fewer did.
fn half_way(mut times: Vec<f64>, count: usize) -> Option<f64> {
    let half = count.div_ceil(2).max(1);
    times.sort_by(f64::total_cmp);
    times.get(half - 1).copied()
}

/// The share of every balloon counted in each state.
fn share_of(counts: &[GroupCensus], hours: f64) -> Shares {
    let (c, h, f) = counts.iter().fold((0u32, 0u32, 0u32), |(c, h, f), g| {
        (c + g.ceiling, h + g.hovering, f + g.floor)
    });
    let total = f64::from((c + h + f).max(1));
    Shares {
        hours,
        ceiling: f64::from(c) / total,
        hovering: f64::from(h) / total,
        floor: f64::from(f) / total,
    }
}

/// What the table's head says about the run.
struct RunFacts {
    scene: String,
    /// The moving air: "still", or its sources.
    air: String,
    hours: f64,
    wall_s: f64,
    steps: u64,
    jumps: u64,
}

fn print_forecast(run: &RunFacts, groups: &[GroupForecast]) {
    let RunFacts {
        scene,
        air,
        hours,
        wall_s,
        steps,
        jumps,
    } = run;
    let when = |t: Option<f64>| t.map_or_else(|| format!("> {hours} h"), |t| format!("{t:.2} h"));
    print_table(
        "up forecast",
        &[
            ("scene", scene.to_string()),
            ("air", air.to_string()),
            ("simulated", format!("{hours} h")),
            ("wall clock", format!("{wall_s:.1} s")),
            ("steps", steps.to_string()),
            ("time-lapse jumps", jumps.to_string()),
        ],
    );
    let header = [
        "group",
        "balloons",
        "first leaves ceiling",
        "half left ceiling",
        "half on floor",
        "lift left at end",
    ];
    let rows: Vec<[String; 6]> = groups
        .iter()
        .map(|g| {
            let never = g.reached_ceiling == 0;
            let ceiling = |t| {
                if never {
                    "never up".to_string()
                } else {
                    when(t)
                }
            };
            [
                format!("{} ({} {})", g.group, g.kind, g.treatment),
                g.count.to_string(),
                ceiling(g.leaves_ceiling_h.first),
                ceiling(g.leaves_ceiling_h.median),
                when(g.on_floor_h.median),
                format!("{:.1} %", g.mean_lift_fraction_end * 100.0),
            ]
        })
        .collect();
    let mut widths = header.map(str::len);
    for row in &rows {
        for (w, cell) in widths.iter_mut().zip(row) {
            *w = (*w).max(cell.chars().count());
        }
    }
    let line = |cells: &[&str]| {
        let padded: Vec<String> = cells
            .iter()
            .zip(widths)
            .map(|(c, w)| format!("{c:<w$}"))
            .collect();
        println!("  {}", padded.join("  ").trim_end());
    };
    line(&header);
    for row in &rows {
        line(&row.each_ref().map(String::as_str));
    }
}

/// Reads one state's share.
type ShareOf = fn(&Shares) -> f64;

/// The shares against time as an SVG document.
fn plot_svg(shares: &[Shares], hours: f64) -> Result<String> {
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (800, 480)).into_drawing_area();
        let draw = |e| anyhow::anyhow!("--plot: cannot draw the plot: {e:?}");
        root.fill(&WHITE).map_err(draw)?;
        let mut chart = ChartBuilder::on(&root)
            .caption("Where the balloons are", ("sans-serif", 22))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(56)
            .build_cartesian_2d(0.0..hours, -2.0..102.0)
            .map_err(draw)?;
        chart
            .configure_mesh()
            .x_desc("simulated time (h)")
            .y_desc("share of balloons (%)")
            .draw()
            .map_err(draw)?;
        let series: [(&str, RGBColor, ShareOf); 3] = [
            ("at the ceiling", RGBColor(214, 39, 40), |s| s.ceiling),
            ("hovering", RGBColor(31, 119, 180), |s| s.hovering),
            ("on the floor", RGBColor(44, 160, 44), |s| s.floor),
        ];
        for (name, color, value) in series {
            chart
                .draw_series(LineSeries::new(
                    shares.iter().map(|s| (s.hours, value(s) * 100.0)),
                    color.stroke_width(2),
                ))
                .map_err(draw)?
                .label(name)
                .legend(move |(x, y)| PathElement::new([(x, y), (x + 20, y)], color));
        }
        chart
            .configure_series_labels()
            // Left of the middle: balloons leave the ceiling hours into a run.
            .position(SeriesLabelPosition::MiddleLeft)
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .draw()
            .map_err(draw)?;
        root.present().map_err(draw)?;
    }
    Ok(svg)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn half_way_is_the_middle_balloons_time_or_none() {
        assert_eq!(half_way(vec![3.0, 1.0, 2.0], 3), Some(2.0));
        assert_eq!(half_way(vec![4.0, 1.0], 4), Some(4.0));
        assert_eq!(half_way(vec![1.0], 4), None);
        assert_eq!(half_way(vec![], 0), None);
    }

    #[test]
    fn a_balloon_leaves_the_ceiling_once_it_has_been_there() {
        let mut h = History::default();
        h.update(FloatState::Floor, 0.0);
        assert_eq!(h.on_floor, Some(0.0));
        h.update(FloatState::Hovering, 0.1);
        assert_eq!(
            (h.left_ceiling, h.on_floor),
            (None, None),
            "rising is not leaving"
        );
        h.update(FloatState::Ceiling, 0.2);
        h.update(FloatState::Hovering, 5.0);
        h.update(FloatState::Ceiling, 5.5);
        assert_eq!(h.left_ceiling, None, "back up: not left");
        h.update(FloatState::Hovering, 9.0);
        h.update(FloatState::Floor, 10.0);
        h.update(FloatState::Floor, 11.0);
        assert_eq!((h.left_ceiling, h.on_floor), (Some(9.0), Some(10.0)));
    }

    #[test]
    fn shares_add_up_over_the_groups() {
        let g = |ceiling, hovering, floor| GroupCensus {
            ceiling,
            hovering,
            floor,
            mean_lift_fraction: 1.0,
        };
        let s = share_of(&[g(2, 1, 1), g(0, 0, 4)], 3.0);
        assert_eq!((s.ceiling, s.hovering, s.floor), (0.25, 0.125, 0.625));
        assert_eq!(s.hours, 3.0);
    }
}
