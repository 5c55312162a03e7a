//! `up run --body-hashes FILE`: every body's state hashes at the start and
//! after each step, the lines the determinism check compares across builds.

use super::*;
use up_physics::divergence::body_hash_header;

#[test]
fn a_line_a_step_ending_at_the_runs_state_hash() {
    let dir = TempDir::new("body-hashes");
    let file = dir.str("hashes.txt");
    let scene = asset("bouquet.toml");
    let args = [
        "run",
        &scene,
        "--seconds",
        "0.5",
        "--json",
        "--body-hashes",
        &file,
    ];
    let summary = last_json(&up_ok(&args));
    let steps = summary["steps"].as_u64().unwrap();
    let balloons = summary["balloons"].as_u64().unwrap() as usize;
    assert_eq!(steps, 30);
    let text = std::fs::read_to_string(&file).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines[0], body_hash_header());
    assert_eq!(
        lines.len(),
        1 + 1 + steps as usize,
        "the start, then every step"
    );
    for (k, line) in lines[1..].iter().enumerate() {
        let tokens: Vec<&str> = line.split(' ').collect();
        assert_eq!(tokens[0], k.to_string(), "{line}");
        assert_eq!(tokens.len(), 2 + balloons, "{line}");
        for body in &tokens[2..] {
            let (_, hashes) = body.split_once(':').expect("index.generation/user_data:");
            assert_eq!(hashes.split(',').count(), 7, "{body}");
        }
    }
    let last: Vec<&str> = lines.last().unwrap().split(' ').collect();
    assert_eq!(summary["state_hash"].as_str(), Some(last[1]));
    // The same run writes the same lines.
    let again = dir.str("again.txt");
    up_ok(&["run", &scene, "--seconds", "0.5", "--body-hashes", &again]);
    assert_eq!(std::fs::read_to_string(&again).unwrap(), text);
}

#[test]
fn body_hashes_refuse_a_time_lapse() {
    let dir = TempDir::new("body-hashes-hours");
    let file = dir.str("hashes.txt");
    let err = up_err(&["run", "--hours", "1", "--body-hashes", &file]);
    assert!(
        err.contains("--body-hashes") || err.contains("--hours"),
        "{err}"
    );
    assert!(dir.files().is_empty(), "{:?}", dir.files());
}
