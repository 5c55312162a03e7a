//! The shape keys: each bad value names its key path and line.

use super::test_support::toml_err;
use super::*;

fn group(keys: &str) -> Scene {
    Scene::from_toml_str(&format!("[[balloons]]\n{keys}\n"), "test.toml")
        .unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn shapes_parse_and_default_by_kind() {
    assert_eq!(group("count = 1").balloons[0].shape(), BalloonShape::Round);
    assert_eq!(
        group("kind = \"foil\"").balloons[0].shape(),
        BalloonShape::Pillow
    );
    let s = group("kind = \"foil\"\nshape = \"digit\"\ntext = \"7\"\nsize_in = 34");
    let g = &s.balloons[0];
    assert_eq!(g.shape(), BalloonShape::Digit);
    assert_eq!(
        g.outline(),
        Some(crate::balloon::outline::OutlineKind::Digit(7))
    );
    // Two 34″ sheets of the film: more than the 18″ pillow's 9 g.
    assert!(
        g.shaped_envelope_mass_kg() > 0.009,
        "{}",
        g.shaped_envelope_mass_kg()
    );
    let back = Scene::from_toml_str(&s.to_toml_string().unwrap(), "back.toml").unwrap();
    assert_eq!(back.balloons[0], s.balloons[0]);
}

#[test]
fn bad_shape_keys_name_their_key_and_line() {
    let e = toml_err("[[balloons]]\nshape = \"heart\"\n");
    assert_eq!(e.key(), Some("balloons[0].shape"), "{e}");
    assert_eq!(e.line(), Some(2));
    assert!(e.to_string().contains("kind = \"foil\""), "{e}");
    let e = toml_err("[[balloons]]\nkind = \"foil\"\nshape = \"round\"\n");
    assert_eq!(e.key(), Some("balloons[0].shape"), "{e}");
    let e = toml_err("[[balloons]]\nkind = \"foil\"\nshape = \"digit\"\n");
    assert_eq!(e.key(), Some("balloons[0].text"), "{e}");
    let e = toml_err("[[balloons]]\nkind = \"foil\"\nshape = \"digit\"\ntext = \"12\"\n");
    assert_eq!(e.key(), Some("balloons[0].text"), "{e}");
    assert_eq!(e.line(), Some(4));
    let e = toml_err("[[balloons]]\nkind = \"foil\"\nshape = \"star\"\ntext = \"1\"\n");
    assert_eq!(e.key(), Some("balloons[0].text"), "{e}");
    let e = toml_err("[[balloons]]\nmesh = \"a.obj\"\nshape = \"round\"\n");
    assert_eq!(e.key(), Some("balloons[0].shape"), "{e}");
    let e = toml_err("[[balloons]]\nknot = [0.0, 0.0, 0.0]\n");
    assert_eq!(e.key(), Some("balloons[0].knot"), "{e}");
    let e = toml_err("[[balloons]]\nmesh = \"a.obj\"\nknot = [0.0, nan, 0.0]\n");
    assert_eq!(e.key(), Some("balloons[0].knot"), "{e}");
    let e = toml_err("[[balloons]]\nshape = \"oval\"\n");
    assert!(e.to_string().contains("balloons[0].shape"), "{e}");
}

#[test]
fn a_missing_mesh_file_is_named() {
    let scene = group("mesh = \"no-such-balloon.obj\"");
    let e = crate::build::build_world(&scene).err().expect("refused");
    assert_eq!(e.key(), Some("balloons[0].mesh"), "{e}");
    assert!(e.to_string().contains("no-such-balloon.obj"), "{e}");
}
