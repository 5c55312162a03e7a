//! Furniture from the command line: the birthday table validates and
//! exports with its pieces (OBJ and glTF); a piece through a wall exits 2
//! naming the piece, its line and the wall.

use super::*;

#[test]
fn the_birthday_table_validates_and_exports_its_furniture() {
    up_ok(&["validate", &asset("birthday.toml")]);
    let dir = TempDir::new("furniture-export");
    up_ok(&[
        "export-obj",
        &dir.str("obj"),
        "--scene",
        &asset("birthday.toml"),
    ]);
    let obj = std::fs::read_to_string(dir.path("obj").join("scene.obj")).unwrap();
    let pieces = obj
        .lines()
        .filter(|l| l.starts_with("o furniture_"))
        .count();
    assert_eq!(pieces, 5, "a table and four chairs");
    assert!(obj.contains("o furniture_0_table") && obj.contains("usemtl furniture_wood"));

    let glb = dir.str("birthday.glb");
    up_ok(&[
        "export-gltf",
        &asset("birthday.toml"),
        &glb,
        "--seconds",
        "0.1",
    ]);
    let bytes = std::fs::read(&glb).unwrap();
    let json_len = u32::from_le_bytes(bytes[12..16].try_into().unwrap()) as usize;
    let json: Value = serde_json::from_slice(&bytes[20..20 + json_len]).unwrap();
    let names: Vec<&str> = json["nodes"]
        .as_array()
        .unwrap()
        .iter()
        .filter_map(|n| n["name"].as_str())
        .collect();
    assert!(names.contains(&"furniture"), "{names:?}");
}

#[test]
fn a_piece_through_a_wall_exits_2_naming_it_its_line_and_the_wall() {
    let dir = TempDir::new("furniture-wall");
    let scene = dir.path("wall.toml");
    std::fs::write(
        &scene,
        "[room]\nwidth = 4\n\n[[furniture]]\nkind = \"table\"\nposition = [1.7, 0, 0]\n",
    )
    .unwrap();
    let err = up_err(&["validate", &scene.display().to_string()]);
    assert!(
        err.contains("wall.toml:6: furniture[0].position") && err.contains("wall at x = 2"),
        "{err}"
    );
}
