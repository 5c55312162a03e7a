//! `bench`, `colliders`, `export-obj` and `fit-spheres`.

use super::*;

#[test]
fn bench_reports_timings_and_stages() {
    let text = up_ok(&["bench", "--balloons", "3", "--steps", "20", "--json"]);
    let j = last_json(&text);
    assert_eq!(j["balloons"], 3);
    assert_eq!(j["steps"], 20);
    for key in [
        "ms_per_step",
        "median_ms",
        "p95_ms",
        "max_ms",
        "wall_seconds",
        "state_hash",
    ] {
        assert!(j[key].is_number() || j[key].is_string(), "{key} in {j}");
    }
    // One mean per stage, in step order, then the total; the phases sum them.
    let stages = j["stages"].as_array().unwrap();
    let names: Vec<&str> = stages.iter().map(|s| s["name"].as_str().unwrap()).collect();
    assert_eq!(names.first(), Some(&"gas"), "{j}");
    assert_eq!(names.last(), Some(&"total"), "{j}");
    assert!(
        names.contains(&"solve") && names.contains(&"prepare_ribbons"),
        "{j}"
    );
    let ms = |s: &serde_json::Value| s["ms_per_step"].as_f64().unwrap();
    let sum = |list: &[serde_json::Value]| list[..list.len() - 1].iter().map(ms).sum::<f64>();
    let total = ms(stages.last().unwrap());
    assert!((sum(stages) - total).abs() <= 1e-9 * total.max(1.0), "{j}");
    let phases = j["phases"].as_array().unwrap();
    assert!(phases.len() < stages.len(), "{j}");
    assert!((sum(phases) - total).abs() <= 1e-9 * total.max(1.0), "{j}");
    up_err(&["bench", "--steps", "0"]);
    up_err(&["bench", "no-such-scene.toml"]);
}

#[test]
fn colliders_show_the_default_tree_and_mass() {
    let text = up_ok(&["colliders"]);
    assert!(
        text.contains("node  0") && text.contains("mass properties"),
        "{text}"
    );
    let j = last_json(&up_ok(&["colliders", "--json"]));
    let nodes = j["nodes"].as_array().unwrap();
    assert_eq!(nodes.iter().filter(|n| n["leaf"] == true).count(), 5, "{j}");
    assert_eq!(nodes[0]["leaf"], false);
    let mass = j["mass_kg"].as_f64().unwrap();
    assert!((0.002..0.02).contains(&mass), "{mass}");
    assert!(j["coverage"].as_f64().unwrap() > 0.99, "{j}");
}

#[test]
fn export_obj_writes_meshes_and_fit_spheres_reads_them_back() {
    let dir = TempDir::new("export");
    let out = dir.path("assets");
    let listed = up_ok(&["export-obj", &out.display().to_string()]);
    let balloon = out.join("balloon.obj");
    assert!(balloon.exists(), "{listed}");
    let written: Vec<&str> = listed.lines().collect();
    assert!(written.iter().any(|l| l.ends_with(".mtl")), "{listed}");
    assert!(written.iter().all(|l| Path::new(l).exists()), "{listed}");

    let json = dir.str("fit.json");
    up_ok(&[
        "fit-spheres",
        &balloon.display().to_string(),
        "--leaves",
        "5",
        "--out",
        &json,
    ]);
    let fit: Value = serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    assert!(fit["coverage"].as_f64().unwrap() > 0.99, "{fit}");
    assert!(fit["tree"].is_object(), "{fit}");
    // Without --out the JSON goes to standard output.
    let printed: Value =
        serde_json::from_str(&up_ok(&["fit-spheres", &balloon.display().to_string()])).unwrap();
    assert_eq!(printed["coverage"], fit["coverage"]);

    up_err(&["fit-spheres", &dir.str("absent.obj")]);
    up_err(&[
        "fit-spheres",
        &balloon.display().to_string(),
        "--leaves",
        "0",
    ]);
    std::fs::write(dir.path("open.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
    up_err(&["fit-spheres", &dir.str("open.obj")]);
    let before = dir.files();
    up_err(&[
        "fit-spheres",
        &balloon.display().to_string(),
        "--out",
        &dir.str("no/dir/fit.json"),
    ]);
    assert_eq!(dir.files(), before);
}
