//! `up run --probe ID --probe-out FILE.csv`: one balloon's forces every
//! step, as the engine integrated them (`up_physics::ForceBreakdown`), the
//! numbers the web app draws as arrows, and the moving air's velocity at
//! the balloon, which its drag acts against.

use std::io::Write;
use std::path::PathBuf;

use anyhow::{bail, Context, Result};
use clap::Args;
use up_physics::{BodyId, ForceBreakdown, ForceProbe, World};
use up_scene::atomic_file::AtomicFile;

/// The forces of a row, in order, each as x, y and z columns.
const FORCES: [&str; 6] = ["weight", "buoyancy", "drag", "contact", "ribbon", "other"];

#[derive(Args, Debug)]
pub struct ProbeArgs {
    /// Write the forces on balloon ID (its id as --out numbers them) every
    /// step to --probe-out.
    #[arg(
        long,
        value_name = "ID",
        requires = "probe_out",
        conflicts_with = "hours",
        allow_negative_numbers = true
    )]
    pub probe: Option<i64>,
    /// The probe's CSV: `t,fx_weight,fy_weight,fz_weight,fx_buoyancy,...` with
    /// weight, buoyancy, drag (against the air's velocity relative to the
    /// balloon), contact (room and balloons), ribbon and other (a hand's
    /// pull, force fields): s, then N, world frame, Y up, each its mean over
    /// the step that ends at t; then `ux_air,uy_air,uz_air`, the moving
    /// air's velocity at the balloon over that step, m/s.
    #[arg(long, value_name = "FILE.csv", requires = "probe")]
    pub probe_out: Option<PathBuf>,
}

/// The probe's CSV being written, whole or not at all.
pub struct ProbeCsv {
    file: AtomicFile,
    path: PathBuf,
    body: BodyId,
}

/// The header: `t`, three columns per force, and three for the air's velocity.
pub fn header() -> String {
    let mut columns = vec!["t".to_string()];
    for force in FORCES {
        columns.extend(["x", "y", "z"].map(|axis| format!("f{axis}_{force}")));
    }
    columns.extend(["x", "y", "z"].map(|axis| format!("u{axis}_air")));
    columns.join(",")
}

impl ProbeCsv {
    /// Checks the id against `world`'s balloons, probes it, and creates the
    /// file with its header; None without `--probe`.
    pub fn create(args: &ProbeArgs, world: &mut World) -> Result<Option<ProbeCsv>> {
        let (Some(id), Some(path)) = (args.probe, &args.probe_out) else {
            return Ok(None);
        };
        let body = world
            .body_ids()
            .iter()
            .copied()
            .find(|b| i64::from(b.index) == id);
        let Some(body) = body else {
            let ids = world.body_ids().iter().map(|b| b.index);
            let (lo, hi) = (ids.clone().min(), ids.max());
            match (lo, hi) {
                (Some(lo), Some(hi)) => bail!(
                    "--probe {id}: expected a balloon id from {lo} to {hi}, as --out numbers the balloons"
                ),
                _ => bail!("--probe {id}: the scene has no balloons to probe"),
            }
        };
        let mut file = AtomicFile::create(path)?;
        writeln!(file, "{}", header())
            .with_context(|| format!("cannot write {}", path.display()))?;
        world.set_force_probe(ForceProbe::One(body));
        Ok(Some(ProbeCsv {
            file,
            path: path.clone(),
            body,
        }))
    }

    /// The row of the step just taken (none once the balloon is gone).
    pub fn write(&mut self, world: &World) -> Result<()> {
        let Some(f) = world.probed_forces(self.body) else {
            return Ok(());
        };
        self.row(world.time(), &f)
            .with_context(|| format!("cannot write {}", self.path.display()))
    }

    fn row(&mut self, t: f64, f: &ForceBreakdown) -> std::io::Result<()> {
        write!(self.file, "{t}")?;
        for v in [
            f.weight, f.buoyancy, f.drag, f.contact, f.ribbon, f.other, f.air,
        ] {
            // + 0 turns −0 (a zero component of −ρ·V·g, say) into 0.
            let v = v + glam::Vec3::ZERO;
            write!(self.file, ",{},{},{}", v.x, v.y, v.z)?;
        }
        writeln!(self.file)
    }

    pub fn commit(self) -> Result<()> {
        self.file.commit()?;
        Ok(())
    }
}
