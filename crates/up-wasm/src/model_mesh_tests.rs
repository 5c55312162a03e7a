use super::*;
use crate::state::State;

const TWO_GROUPS: &str = r#"
[[balloons]]
count = 2
size_in = 11

[[balloons]]
kind = "foil"
count = 3
size_in = 18
"#;

fn two_groups() -> State {
    let mut s = State::default();
    s.load_toml(TWO_GROUPS)
        .expect("a latex and a foil group build");
    s
}

#[test]
fn the_page_learns_which_models_are_foil() {
    let s = State::default();
    assert_eq!(s.model_foil(), Err(WasmError::NoWorld));
    assert_eq!(two_groups().model_foil().unwrap(), vec![false, true]);
    let mut s = State::default();
    s.load_default().unwrap();
    assert!(s.model_foil().unwrap().iter().all(|foil| !foil));
}

#[test]
fn a_foil_model_s_mesh_is_the_engine_s_in_flat_arrays() {
    let mut s = two_groups();
    let n = s.write_model_mesh(1).unwrap();
    let mesh = &s.loaded().unwrap().built.balloon_models[1].mesh;
    assert_eq!(n, mesh.positions.len());
    assert!(n > 100, "{n} vertices");
    assert_eq!(s.mesh.positions.len(), n * MESH_VERTEX_FLOATS);
    assert_eq!(s.mesh.normals.len(), n * MESH_VERTEX_FLOATS);
    assert_eq!(s.mesh.indices.len(), mesh.indices.len() * 3);
    assert!(s.mesh.indices.iter().all(|&i| (i as usize) < n));
    let last = n - 1;
    assert_eq!(
        s.mesh.positions[last * 3..last * 3 + 3],
        mesh.positions[last].to_array()
    );
    assert_eq!(s.mesh.indices[..3], mesh.indices[0]);
    for v in s.mesh.normals.chunks(3) {
        let len = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        assert!((len - 1.0).abs() < 1e-3, "unit normals: {v:?}");
    }
    // An 18″ pillow: about 46 cm across, much thinner than wide.
    let extent = |axis: usize| {
        let c = s.mesh.positions.iter().skip(axis).step_by(3);
        c.clone().fold(f32::MIN, |a, &b| a.max(b)) - c.fold(f32::MAX, |a, &b| a.min(b))
    };
    let (x, z) = (extent(0), extent(2));
    assert!(x.max(z) > 0.35 && x.max(z) < 0.5, "{x} × {z}");
    assert!(x.min(z) < 0.5 * x.max(z), "{x} × {z}");
}

#[test]
fn a_missing_model_is_refused_and_the_last_mesh_stays() {
    let mut s = State::default();
    assert_eq!(s.write_model_mesh(0), Err(WasmError::NoWorld));
    let mut s = two_groups();
    let n = s.write_model_mesh(1).unwrap();
    assert!(
        matches!(s.write_model_mesh(2), Err(WasmError::OutOfRange(m)) if m.contains("2 models"))
    );
    assert_eq!(s.mesh.positions.len(), n * 3);
}
