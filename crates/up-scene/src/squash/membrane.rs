//! The membrane as a spring: its contact stiffness and the dent one contact
//! leaves (the model is described in `mod.rs`).

/// Floats per body in the squash table: nx·d, ny·d, nz·d, reach.
pub const SQUASH_FLOATS: usize = 4;
/// Overpressure of an inflated balloon, Pa: the middle of the physics
/// reference's 1–3 kPa. With it an 11″ balloon thrown at 5 m/s into a wall
/// dents ≈ 1.4 cm (≈ 2 cm at 1 kPa).
pub const MEMBRANE_OVERPRESSURE_PA: f32 = 2000.0;
/// Deepest dent drawn, as a fraction of the balloon's radius: past that the
/// small-dent stiffness no longer holds, and a flattened quarter reads as a
/// squash already.
pub const MAX_SQUASH_FRACTION: f32 = 0.25;
/// Shallowest dent written, m: under a millimetre nothing shows on a 28 cm
/// balloon, and a pile at rest stays exactly round.
pub const MIN_SQUASH_M: f32 = 0.001;

/// Contact stiffness of a balloon's membrane, N/m: 2π·R·Δp (R m, Δp Pa).
pub fn membrane_stiffness(radius: f32, overpressure: f32) -> f32 {
    std::f32::consts::TAU * radius * overpressure
}

/// One side of a contact: its membrane stiffness (N/m) and effective mass (kg).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Membrane {
    pub stiffness: f32,
    pub mass: f32,
}

/// The dent of membrane `own`, m, from a contact against `other` (None: the
/// room, rigid and immovable) whose impulse over the step of `dt` s was
/// `step_impulse` and whose largest impulse within one substep was
/// `peak_impulse` (N·s), with restitution `restitution`; not capped.
pub fn contact_depth(
    peak_impulse: f32,
    step_impulse: f32,
    restitution: f32,
    dt: f32,
    own: Membrane,
    other: Option<Membrane>,
) -> f32 {
    let (stiffness, mass) = match other {
        None => (own.stiffness, own.mass),
        Some(o) => (
            own.stiffness * o.stiffness / (own.stiffness + o.stiffness),
            own.mass * o.mass / (own.mass + o.mass),
        ),
    };
    if !(stiffness > 0.0 && mass > 0.0 && own.stiffness > 0.0) {
        return 0.0;
    }
    // The approach momentum m·v, and the peak force v·√(k·m).
    let approach = peak_impulse.min(step_impulse / (1.0 + restitution.max(0.0)));
    let impact_force = approach * (stiffness / mass).sqrt();
    let load_force = if dt > 0.0 { step_impulse / dt } else { 0.0 };
    let force = impact_force.max(load_force);
    if force > 0.0 {
        force / own.stiffness
    } else {
        0.0
    }
}
