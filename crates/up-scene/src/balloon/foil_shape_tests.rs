use super::*;
use up_geom::fit::check_closed;
use up_geom::fit::mesh_integrals::{shell_integrals, solid_integrals};

fn all_kinds() -> Vec<OutlineKind> {
    [OutlineKind::Disc, OutlineKind::Heart, OutlineKind::Star]
        .into_iter()
        .chain((0..10).map(OutlineKind::Digit))
        .collect()
}

#[test]
fn paulsens_profile_is_b_at_the_centre_and_nothing_at_the_rim() {
    assert!((paulsen_profile(0.0) - f64::from(PAULSEN_B)).abs() < 1e-5);
    assert!(paulsen_profile(1.0).abs() < 1e-12);
    // Near the rim it rises as √(1 − x).
    let x = 1.0 - 1e-4;
    assert!((paulsen_profile(x) / 1e-2 - 1.0).abs() < 1e-3);
}

#[test]
fn a_round_foil_is_paulsens_mylar_balloon() {
    let a = 0.5 * 18.0 * 0.0254;
    let s = foil_shape(OutlineKind::Disc, 2.0 * a).unwrap();
    let m = &s.mesh;
    assert!(check_closed(&m.positions, &m.indices).is_ok());
    let r = a / PAULSEN_A;
    let v = solid_integrals(&m.positions, &m.indices).volume;
    let paulsen = 2.0 / 3.0 * std::f32::consts::PI * a * r * r;
    assert!(
        (v / paulsen - 1.0).abs() < 0.01,
        "V = {v} m³, Paulsen {paulsen} m³"
    );
    let b = up_geom::Aabb::from_points(&m.positions).extents();
    assert!((b.x / (2.0 * r) - 1.0).abs() < 0.01, "width {}", b.x);
    assert!(
        (b.z / (2.0 * PAULSEN_B * r) - 1.0).abs() < 0.01,
        "thickness {}",
        b.z
    );
    // Surface π² r² (the discs' 2πa² less the crimp).
    let area = shell_integrals(&m.positions, &m.indices).area;
    let expected = std::f32::consts::PI.powi(2) * r * r;
    assert!(
        (area / expected - 1.0).abs() < 0.02,
        "area {area} vs {expected}"
    );
    assert!((s.sheet_area_m2 / (std::f32::consts::PI * a * a) - 1.0).abs() < 0.01);
    // The valve at the bottom of the rim.
    assert!((m.dimensions.neck_bottom_y + r).abs() < 0.01 * r);
}

#[test]
fn every_outline_makes_a_closed_outward_balloon() {
    for kind in all_kinds() {
        let s = foil_shape(kind, 0.8636).unwrap();
        let m = &s.mesh;
        check_closed(&m.positions, &m.indices).unwrap_or_else(|e| panic!("{kind:?}: {e}"));
        let solid = solid_integrals(&m.positions, &m.indices);
        assert!(solid.volume > 0.0, "{kind:?}: V = {}", solid.volume);
        assert!(m.positions.iter().all(|p| p.is_finite()));
        assert!(s.frontal_area_m2 > 0.0 && s.sheet_area_m2 > 0.0);
        let k = m.dimensions.knot_center;
        assert!(k.y < solid.centroid.y, "{kind:?}: valve above the centre");
    }
}

#[test]
fn the_shapes_scale_with_their_size() {
    let v = |size| {
        let m = foil_shape(OutlineKind::Heart, size).unwrap().mesh;
        solid_integrals(&m.positions, &m.indices).volume
    };
    assert!((v(0.9) / v(0.45) - 8.0).abs() < 0.01 * 8.0);
    assert!(foil_shape(OutlineKind::Star, f32::NAN).is_err());
}
