// The model's own tests (depths against the closed forms, a wall, a pile)
// are up-scene's (`up_scene::squash`); these hold the page's table to them.
use super::*;
use crate::state::State;

/// One 11″ balloon carried into the +x wall by gravity along −x (its buoyancy).
const WALL_SCENE: &str =
    "[room]\nwidth = 6.0\ndepth = 3.0\nwall_height = 3.0\nceiling = \"flat\"\n\n\
     [[balloons]]\ncount = 1\ntilt_deg = 0\nyaw_deg = 0\n\
     spawn = { min = [0.4, 1.0, -0.4], max = [1.0, 1.9, 0.4] }\n\n\
     [sim]\ngravity = [-80.0, 0.0, 0.0]\n";

#[test]
fn the_page_reads_each_dent_once_toward_the_wall() {
    let mut state = State::default();
    assert!(state.write_body_squash().is_err(), "no world");
    state.load_toml(WALL_SCENE).unwrap();
    let mut dent = None;
    for _ in 0..600 {
        state.step(1).unwrap();
        state.write_body_squash().unwrap();
        assert_eq!(state.squash.out.len(), SQUASH_FLOATS);
        let v = &state.squash.out;
        if v[0] != 0.0 {
            dent = Some([v[0], v[1], v[2], v[3]]);
            break;
        }
    }
    let [x, y, z, reach] = dent.expect("the balloon reached the wall");
    let depth = (x * x + y * y + z * z).sqrt();
    assert!(
        x / depth > 0.95 && (0.009..0.02).contains(&depth),
        "{x} {y} {z}"
    );
    assert!((0.12..0.2).contains(&reach), "{reach}");
    state.write_body_squash().unwrap();
    assert!(state.squash.out.iter().all(|&v| v == 0.0), "read once");
}
