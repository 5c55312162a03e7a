//! `up export-gltf`: the animation read back from the `.glb` (a small GLB
//! reader over gltf-json) gives every balloon where `up run --out` has it
//! and every ribbon joint where `--ribbons-out` has it, at the same times;
//! bad arguments exit 2 naming the flag and write nothing.

use std::collections::HashMap;

use gltf_json::{animation::Property, validation::Checked, Root};

use super::*;

/// A `.glb` split into its document and binary chunk.
struct Glb {
    root: Root,
    bin: Vec<u8>,
}

impl Glb {
    fn read(path: &str) -> Glb {
        let bytes = std::fs::read(path).unwrap();
        let word = |at: usize| u32::from_le_bytes(bytes[at..at + 4].try_into().unwrap()) as usize;
        assert_eq!(&bytes[0..4], b"glTF");
        assert_eq!(word(4), 2, "glTF 2");
        assert_eq!(word(8), bytes.len(), "the header's length");
        let json_len = word(12);
        assert_eq!(&bytes[16..20], b"JSON");
        let root = Root::from_slice(&bytes[20..20 + json_len]).unwrap();
        let bin_at = 20 + json_len;
        assert_eq!(&bytes[bin_at + 4..bin_at + 8], b"BIN\0");
        let bin = bytes[bin_at + 8..bin_at + 8 + word(bin_at)].to_vec();
        Glb { root, bin }
    }

    /// The floats of accessor `index`.
    fn floats(&self, index: usize) -> Vec<f32> {
        let accessor = &self.root.accessors[index];
        let view = &self.root.buffer_views[accessor.buffer_view.unwrap().value()];
        let start = view.byte_offset.map_or(0, |o| o.0 as usize)
            + accessor.byte_offset.map_or(0, |o| o.0 as usize);
        self.bin[start..start + view.byte_length.0 as usize]
            .chunks_exact(4)
            .map(|b| f32::from_le_bytes(b.try_into().unwrap()))
            .collect()
    }

    /// Each node's translation keys, by name: (the run's time, position).
    fn translation_paths(&self) -> HashMap<String, Vec<(f64, [f32; 3])>> {
        let up = &self.root.scenes[0].extras.as_ref().unwrap();
        let up: Value = serde_json::from_str(up.get()).unwrap();
        let start = up["up"]["start_s"].as_f64().unwrap();
        let scale = up["up"]["sim_seconds_per_second"].as_f64().unwrap();
        let animation = &self.root.animations[0];
        let mut paths = HashMap::new();
        for channel in &animation.channels {
            if channel.target.path != Checked::Valid(Property::Translation) {
                continue;
            }
            let sampler = &animation.samplers[channel.sampler.value()];
            let times = self.floats(sampler.input.value());
            let values = self.floats(sampler.output.value());
            let node = &self.root.nodes[channel.target.node.value()];
            let keys = times
                .iter()
                .zip(values.chunks_exact(3))
                .map(|(&t, v)| (start + f64::from(t) * scale, [v[0], v[1], v[2]]))
                .collect();
            paths.insert(node.name.clone().unwrap(), keys);
        }
        paths
    }
}

/// The CSV row set nearest `t` (its time within 1e-4 s), keyed by its id columns.
fn rows_at(rows: &[Vec<f64>], t: f64, ids: usize) -> HashMap<Vec<i64>, [f64; 3]> {
    rows.iter()
        .filter(|r| (r[0] - t).abs() < 1e-4)
        .map(|r| {
            let key = r[1..1 + ids].iter().map(|&x| x as i64).collect();
            (key, [r[1 + ids], r[2 + ids], r[3 + ids]])
        })
        .collect()
}

fn gap(a: [f32; 3], b: [f64; 3]) -> f64 {
    (0..3)
        .map(|i| (f64::from(a[i]) - b[i]).powi(2))
        .sum::<f64>()
        .sqrt()
}

#[test]
fn the_exported_animation_is_the_run_to_a_hundredth_of_a_millimetre() {
    let dir = TempDir::new("export-gltf");
    let scene = dir.str("scene.toml");
    std::fs::write(
        &scene,
        "[[balloons]]\ncount = 3\ncolors = [\"red\", \"blue\"]\n\
         [balloons.ribbon]\nlength_m = 0.6\nsegments = 4\nweight_g = 0\n\
         [[balloons]]\ncount = 2\nkind = \"foil\"\n\
         [[balloons]]\ncount = 1\nfinish = \"pearl\"\n",
    )
    .unwrap();
    let glb = dir.str("run.glb");
    let said = up_ok(&[
        "export-gltf",
        &scene,
        &glb,
        "--seconds",
        "0.5",
        "--fps",
        "30",
        "--from",
        "0.25",
    ]);
    assert!(said.contains("16 frames"), "{said}");
    let (poses, ribbons) = (dir.str("poses.csv"), dir.str("ribbons.csv"));
    up_ok(&[
        "run",
        &scene,
        "--seconds",
        "0.75",
        "--out",
        &poses,
        "--ribbons-out",
        &ribbons,
    ]);
    let poses = csv_rows(&poses, "t,id,x,y,z,qx,qy,qz,qw");
    let ribbons = csv_rows(&ribbons, "t,balloon,point,x,y,z");
    let paths = Glb::read(&glb).translation_paths();

    let (mut balloons, mut joints) = (0, 0);
    for (name, keys) in &paths {
        assert_eq!(keys.len(), 16, "{name}");
        assert!((keys[0].0 - 0.25).abs() < 1e-4, "{name} starts at --from");
        let parts: Vec<i64> = name
            .split('-')
            .skip(1)
            .map(|p| p.parse().unwrap())
            .collect();
        for &(t, p) in keys {
            let (rows, key) = if name.starts_with("balloon-") {
                (rows_at(&poses, t, 1), parts.clone())
            } else {
                (rows_at(&ribbons, t, 2), parts.clone())
            };
            let want = rows.get(&key).unwrap_or_else(|| panic!("{name} at {t} s"));
            assert!(gap(p, *want) < 1e-5, "{name} at {t} s: {p:?} vs {want:?}");
        }
        if name.starts_with("balloon-") {
            balloons += 1;
        } else {
            assert!(name.starts_with("ribbon-"), "{name}");
            joints += 1;
        }
    }
    assert_eq!(balloons, 6, "every balloon animated");
    assert_eq!(joints, 3 * 5, "every ribbon point a joint");
    // The balloons moved: the comparison is not of a still scene.
    let first = &paths["balloon-0"];
    assert!(first[0].1[1] != first[15].1[1]);
}

#[test]
fn the_document_names_its_parts_and_their_looks() {
    let dir = TempDir::new("export-gltf-looks");
    let glb = dir.str("bouquet.glb");
    up_ok(&[
        "export-gltf",
        &asset("bouquet.toml"),
        &glb,
        "--seconds",
        "0.1",
    ]);
    let root = Glb::read(&glb).root;
    let names: Vec<&str> = root
        .nodes
        .iter()
        .filter_map(|n| n.name.as_deref())
        .collect();
    for name in [
        "room",
        "room-floor",
        "room-walls",
        "camera",
        "key-light",
        "fill-lamp",
    ] {
        assert!(names.contains(&name), "{name} in {names:?}");
    }
    assert!(names.iter().any(|n| n.starts_with("weight-")), "{names:?}");
    assert!(names.iter().any(|n| n.ends_with("-strip")), "{names:?}");
    assert_eq!(
        root.skins.len(),
        names.iter().filter(|n| n.ends_with("-strip")).count()
    );
    for ext in [
        "KHR_lights_punctual",
        "KHR_materials_clearcoat",
        "KHR_materials_transmission",
    ] {
        assert!(root.extensions_used.iter().any(|e| e == ext), "{ext}");
    }
}

#[test]
fn a_time_lapse_shrinks_the_balloons_with_a_scale_channel() {
    let dir = TempDir::new("export-gltf-hours");
    let scene = dir.str("scene.toml");
    std::fs::write(
        &scene,
        "[[balloons]]\ncount = 2\nfilled_hours_before = 20\n",
    )
    .unwrap();
    let glb = dir.str("lapse.glb");
    let said = up_ok(&["export-gltf", &scene, &glb, "--hours", "0.1", "--fps", "24"]);
    assert!(said.contains("7 frames"), "{said}");
    let glb = Glb::read(&glb);
    let animation = &glb.root.animations[0];
    let scale = animation
        .channels
        .iter()
        .find(|c| c.target.path == Checked::Valid(Property::Scale))
        .expect("a scale channel");
    let keys = glb.floats(animation.samplers[scale.sampler.value()].output.value());
    assert!(keys[keys.len() - 1] < keys[0], "shrinks: {keys:?}");
    let up: Value =
        serde_json::from_str(glb.root.scenes[0].extras.as_ref().unwrap().get()).unwrap();
    assert_eq!(up["up"]["sim_seconds_per_second"], 60.0 * 24.0);
}

#[test]
fn bad_arguments_exit_2_naming_the_flag_and_write_nothing() {
    let dir = TempDir::new("export-gltf-bad");
    let scene = asset("bouquet.toml");
    let out = dir.str("x.glb");
    for (args, flag) in [
        (vec!["--fps", "0"], "--fps"),
        (vec!["--fps", "nan"], "--fps"),
        (vec!["--seconds", "-1"], "--seconds"),
        (vec!["--hours", "0"], "--hours"),
        (vec!["--from", "-2"], "--from"),
        (vec!["--seconds", "1", "--hours", "1"], "--seconds"),
    ] {
        let mut all = vec!["export-gltf", scene.as_str(), out.as_str()];
        all.extend(&args);
        let err = up_err(&all);
        assert!(err.contains(flag), "{args:?}: {err}");
    }
    let missing = dir.str("no/such/dir/x.glb");
    up_err(&["export-gltf", &scene, &missing, "--seconds", "0.1"]);
    assert!(dir.files().is_empty(), "{:?}", dir.files());
}
