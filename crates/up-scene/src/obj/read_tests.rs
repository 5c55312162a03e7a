//! OBJ reading tests.

use std::path::{Path, PathBuf};

use super::read::*;

/// A fresh, empty directory under the system temp dir for one test.
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("up-scene-obj-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

/// A unit cube as six separate quads, each with its own four vertices (as
/// some exporters write it): welding must make it closed.
const SPLIT_CUBE: &str = "\
o cube
v 0 0 0\nv 0 1 0\nv 1 1 0\nv 1 0 0\nf 1 2 3 4
v 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\nf 5 6 7 8
v 0 0 0\nv 1 0 0\nv 1 0 1\nv 0 0 1\nf 9 10 11 12
v 0 1 0\nv 0 1 1\nv 1 1 1\nv 1 1 0\nf 13 14 15 16
v 0 0 0\nv 0 0 1\nv 0 1 1\nv 0 1 0\nf 17 18 19 20
v 1 0 0\nv 1 1 0\nv 1 1 1\nv 1 0 1\nf 21 22 23 24
";

#[test]
fn quads_are_triangulated_and_split_vertices_welded() {
    let dir = scratch("cube");
    let mesh = read_obj_mesh(&write(&dir, "cube.obj", SPLIT_CUBE)).unwrap();
    assert_eq!(mesh.vertices().len(), 8);
    assert_eq!(mesh.triangles().len(), 12);
    assert!(mesh.check_closed().is_ok());
    let v = up_geom::fit::mesh_integrals::solid_integrals(mesh.vertices(), mesh.triangles());
    assert!((v.volume - 1.0).abs() < 1e-6, "{}", v.volume);
}

#[test]
fn missing_file_is_reported_by_name() {
    let e = read_obj_mesh(Path::new("/nonexistent/ball.obj")).unwrap_err();
    assert!(matches!(e, ObjError::Missing { .. }));
    assert_eq!(e.to_string(), "/nonexistent/ball.obj: file not found");
}

#[test]
fn malformed_lines_name_the_file_and_line() {
    let dir = scratch("bad");
    let p = write(&dir, "a.obj", "v 0 0 0\nv 1 0 zero\nv 0 1 0\nf 1 2 3\n");
    let e = read_obj_mesh(&p).unwrap_err();
    assert!(matches!(e, ObjError::Malformed { line: 2, .. }), "{e}");
    assert!(e.to_string().contains("a.obj:2: expected a number"), "{e}");

    let p = write(&dir, "b.obj", "v 0 0 0\nv 1 0\nf 1 2 1\n");
    assert!(matches!(
        read_obj_mesh(&p),
        Err(ObjError::Malformed { line: 2, .. })
    ));

    let p = write(&dir, "c.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n");
    assert!(matches!(
        read_obj_mesh(&p),
        Err(ObjError::Malformed { line: 4, .. })
    ));

    let p = write(&dir, "d.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 x 3\n");
    assert!(matches!(
        read_obj_mesh(&p),
        Err(ObjError::Malformed { line: 4, .. })
    ));
}

#[test]
fn nan_coordinates_are_rejected() {
    let dir = scratch("nan");
    let p = write(&dir, "n.obj", "v 0 0 0\nv NaN 0 0\nv 0 1 0\nf 1 2 3\n");
    let e = read_obj_mesh(&p).unwrap_err();
    assert!(matches!(e, ObjError::NonFinite { line: 2, .. }), "{e}");
    let p = write(&dir, "i.obj", "v 0 0 0\nv inf 0 0\nv 0 1 0\nf 1 2 3\n");
    assert!(matches!(
        read_obj_mesh(&p),
        Err(ObjError::NonFinite { line: 2, .. })
    ));
}

#[test]
fn files_without_triangles_are_rejected() {
    let dir = scratch("empty");
    let p = write(&dir, "e.obj", "# nothing\nv 0 0 0\n");
    let e = read_obj_mesh(&p).unwrap_err();
    assert!(matches!(e, ObjError::NoTriangles { .. }));
    assert!(e
        .to_string()
        .ends_with("no triangles (expected at least one face `f a b c`)"));
}

#[test]
fn face_indices_out_of_range_are_rejected() {
    let dir = scratch("range");
    let p = write(&dir, "r.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n");
    let e = read_obj_mesh(&p).unwrap_err();
    assert!(
        matches!(
            e,
            ObjError::IndexOutOfRange {
                line: 4,
                index: 4,
                count: 3,
                ..
            }
        ),
        "{e}"
    );
    let p = write(&dir, "z.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n");
    assert!(matches!(
        read_obj_mesh(&p),
        Err(ObjError::IndexOutOfRange { index: 0, .. })
    ));
    // Negative (relative) indices are fine when they stay in range.
    let p = write(&dir, "neg.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\n");
    assert_eq!(read_obj_mesh(&p).unwrap().triangles().len(), 1);
    let p = write(
        &dir,
        "neg_bad.obj",
        "v 0 0 0\nv 1 0 0\nf -3 -2 -1\nv 0 1 0\n",
    );
    assert!(matches!(
        read_obj_mesh(&p),
        Err(ObjError::IndexOutOfRange { index: -3, .. })
    ));
}

#[test]
fn open_mesh_fails_the_closed_check_naming_the_file() {
    let dir = scratch("open");
    let p = write(
        &dir,
        "open.obj",
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\n",
    );
    let mesh = read_obj_mesh(&p).unwrap();
    let e = mesh.check_closed().unwrap_err();
    assert!(
        e.to_string().contains("open.obj: the mesh is not closed"),
        "{e}"
    );
}

#[test]
fn degenerate_triangles_are_tolerated() {
    let dir = scratch("degenerate");
    let text = format!("{SPLIT_CUBE}f 1 1 2\n");
    let mesh = read_obj_mesh(&write(&dir, "d.obj", &text)).unwrap();
    assert_eq!(mesh.check_closed().unwrap().degenerate_triangles, 1);
}

#[test]
fn non_manifold_and_inconsistent_meshes_fail_the_closed_check() {
    let dir = scratch("manifold");
    // Two cubes sharing one edge: that edge has four triangles.
    let mut text = String::from(SPLIT_CUBE);
    text.push_str("v 1 1 0\nv 2 1 0\nv 2 2 0\nv 1 2 0\nv 1 1 1\nv 2 1 1\nv 2 2 1\nv 1 2 1\n");
    for f in [
        "25 28 27 26",
        "29 30 31 32",
        "25 26 30 29",
        "28 32 31 27",
        "25 29 32 28",
        "26 27 31 30",
    ] {
        text.push_str(&format!("f {f}\n"));
    }
    let mesh = read_obj_mesh(&write(&dir, "two.obj", &text)).unwrap();
    let e = mesh.check_closed().unwrap_err();
    assert!(
        e.to_string()
            .starts_with(&format!("{}: ", dir.join("two.obj").display())),
        "{e}"
    );
    // One face turned the wrong way round.
    let flipped = SPLIT_CUBE.replace("f 1 2 3 4", "f 4 3 2 1");
    let mesh = read_obj_mesh(&write(&dir, "flip.obj", &flipped)).unwrap();
    assert!(mesh.check_closed().is_err());
    // Fitting (what `up fit-spheres` does) refuses an open mesh with the same check.
    let open = SPLIT_CUBE.replace("f 21 22 23 24\n", "");
    let mesh = read_obj_mesh(&write(&dir, "open.obj", &open)).unwrap();
    let fit = up_geom::fit::fit_sphere_tree(
        mesh.vertices(),
        mesh.triangles(),
        &up_geom::fit::FitOptions::with_leaves(5),
    );
    assert!(fit.is_err());
}

#[test]
fn huge_files_are_refused_with_the_cap() {
    let dir = scratch("huge");
    let p = write(&dir, "big.obj", &"v 0 0 0\n".repeat(8));
    let e = read_capped(&p, 32).unwrap_err();
    assert!(matches!(e, ObjError::TooLarge { max: 32, .. }), "{e}");
    assert!(
        e.to_string()
            .ends_with("big.obj: too large: more than 32 bytes (expected an OBJ file of at most 32 bytes, about a million triangles)"),
        "{e}"
    );
    assert_eq!(read_capped(&p, 64).unwrap().len(), 64);
    // A device that never ends stops at MAX_OBJ_BYTES.
    let e = read_obj_mesh(Path::new("/dev/zero")).unwrap_err();
    assert!(
        matches!(
            e,
            ObjError::TooLarge {
                max: MAX_OBJ_BYTES,
                ..
            }
        ),
        "{e}"
    );
    let p = dir.join("bin.obj");
    std::fs::write(&p, [b'v', b' ', 0xff, b'\n']).unwrap();
    assert!(matches!(read_obj_mesh(&p), Err(ObjError::NotText { .. })));
    let e = read_obj_mesh(&dir).unwrap_err();
    assert!(matches!(e, ObjError::Read { .. }), "a directory: {e}");
}

#[test]
fn parsing_text_reports_like_reading_a_file() {
    let e = parse_obj_mesh(
        "v 0 0 0\nv 1 0 0\nv 0 nan 0\nf 1 2 3\n",
        Path::new("mem.obj"),
    )
    .unwrap_err();
    assert_eq!(
        e.to_string(),
        "mem.obj:3: vertex coordinates must be finite numbers, got \"v 0 nan 0\""
    );
    let mesh = parse_obj_mesh(SPLIT_CUBE, Path::new("cube.obj")).unwrap();
    assert_eq!(mesh.triangles().len(), 12);
    // Huge or signless indices, and a vertex far beyond f32, are errors.
    let bad = [
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999999999999\n",
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -99999999999999999999\n",
        "v 0 0 0\nv 1 0 0\nv 0 1e39 0\nf 1 2 3\n",
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 +\n",
    ];
    for text in bad {
        assert!(parse_obj_mesh(text, Path::new("b.obj")).is_err(), "{text}");
    }
}
