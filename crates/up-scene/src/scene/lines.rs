//! Which line of a scene file each key's value starts on, from the parsers
//! themselves: toml's spans (`toml::Spanned`) and serde_json's raw values
//! (`serde_json::value::RawValue`, slices of the text).
//!
//! A parse error carries its own line (the parser's) and key path
//! (`serde_path_to_error`); this index serves the checks that run after
//! parsing, which know a key path but not where it was written. Built only
//! for text that parsed as a scene, it never fails: a value it cannot place
//! just goes without a line.

use std::collections::BTreeMap;
use std::fmt;

use serde::de::{Deserialize, Deserializer, MapAccess, SeqAccess, Visitor};
use serde_json::value::RawValue;
use toml::Spanned;

use super::Scene;
use crate::error::Location;

/// Key paths (`room.width`, `balloons[1].spawn.min`) with the 1-based line
/// where their value starts.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct KeyLines {
    lines: BTreeMap<String, usize>,
}

impl KeyLines {
    /// The line of `path`, or of its nearest ancestor present in the file
    /// (a defaulted `balloons[0].count` points at its `[[balloons]]` table).
    pub fn line_of(&self, path: &str) -> Option<usize> {
        let mut probe = path;
        loop {
            if let Some(&line) = self.lines.get(probe) {
                return Some(line);
            }
            let cut = probe.rfind(['.', '['])?;
            probe = &probe[..cut];
        }
    }

    /// Whether the file gave `path` itself (not just a table above it).
    pub fn contains(&self, path: &str) -> bool {
        self.lines.contains_key(path)
    }

    /// Every value of a TOML document.
    pub fn from_toml(text: &str) -> Self {
        let mut out = KeyLines::default();
        if let Ok(root) = toml::from_str::<TomlNode>(text) {
            out.add_toml(&LineStarts::new(text), String::new(), &root);
        }
        out
    }

    /// Every value of a JSON document.
    pub fn from_json(text: &str) -> Self {
        let mut out = KeyLines::default();
        if let Ok(root) = serde_json::from_str::<&RawValue>(text) {
            out.add_json(text, &LineStarts::new(text), String::new(), root);
        }
        out
    }

    fn add(&mut self, path: String, starts: &LineStarts, offset: usize) {
        if !path.is_empty() {
            self.lines.insert(path, starts.line_of(offset));
        }
    }

    fn add_toml(&mut self, starts: &LineStarts, path: String, node: &TomlNode) {
        match node {
            TomlNode::Table(entries) => {
                for (key, value) in entries {
                    let path = join(&path, key);
                    self.add(path.clone(), starts, value.span().start);
                    self.add_toml(starts, path, value.get_ref());
                }
            }
            TomlNode::Array(items) => {
                for (i, item) in items.iter().enumerate() {
                    let path = format!("{path}[{i}]");
                    self.add(path.clone(), starts, item.span().start);
                    self.add_toml(starts, path, item.get_ref());
                }
            }
            TomlNode::Leaf => {}
        }
    }

    fn add_json(&mut self, text: &str, starts: &LineStarts, path: String, value: &RawValue) {
        let raw = value.get();
        // The raw value is a slice of `text`: its address gives its offset.
        let offset = raw.as_ptr() as usize - text.as_ptr() as usize;
        self.add(path.clone(), starts, offset);
        if raw.starts_with('{') {
            if let Ok(entries) = serde_json::from_str::<BTreeMap<String, &RawValue>>(raw) {
                for (key, value) in entries {
                    self.add_json(text, starts, join(&path, &key), value);
                }
            }
        } else if raw.starts_with('[') {
            if let Ok(items) = serde_json::from_str::<Vec<&RawValue>>(raw) {
                for (i, value) in items.into_iter().enumerate() {
                    self.add_json(text, starts, format!("{path}[{i}]"), value);
                }
            }
        }
    }
}

/// The offsets of a text's newlines, so that a line is found in log time
/// (a scene may hold thousands of values).
struct LineStarts {
    newlines: Vec<usize>,
}

impl LineStarts {
    fn new(text: &str) -> Self {
        let newlines = text
            .bytes()
            .enumerate()
            .filter(|&(_, b)| b == b'\n')
            .map(|(i, _)| i)
            .collect();
        Self { newlines }
    }

    /// 1-based line of a byte offset.
    fn line_of(&self, offset: usize) -> usize {
        self.newlines.partition_point(|&nl| nl < offset) + 1
    }
}

/// 1-based line of a byte offset.
pub fn line_of_offset(text: &str, offset: usize) -> usize {
    LineStarts::new(text).line_of(offset.min(text.len()))
}

fn join(table: &str, key: &str) -> String {
    if table.is_empty() {
        key.to_string()
    } else {
        format!("{table}.{key}")
    }
}

/// A TOML value with the span of every value inside it.
enum TomlNode {
    Table(Vec<(String, Spanned<TomlNode>)>),
    Array(Vec<Spanned<TomlNode>>),
    Leaf,
}

impl<'de> Deserialize<'de> for TomlNode {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct NodeVisitor;

        impl<'de> Visitor<'de> for NodeVisitor {
            type Value = TomlNode;

            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str("any TOML value")
            }

            fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<TomlNode, A::Error> {
                let mut entries = Vec::new();
                while let Some(entry) = map.next_entry()? {
                    entries.push(entry);
                }
                Ok(TomlNode::Table(entries))
            }

            fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<TomlNode, A::Error> {
                let mut items = Vec::new();
                while let Some(item) = seq.next_element()? {
                    items.push(item);
                }
                Ok(TomlNode::Array(items))
            }

            fn visit_bool<E>(self, _: bool) -> Result<TomlNode, E> {
                Ok(TomlNode::Leaf)
            }

            fn visit_i64<E>(self, _: i64) -> Result<TomlNode, E> {
                Ok(TomlNode::Leaf)
            }

            fn visit_u64<E>(self, _: u64) -> Result<TomlNode, E> {
                Ok(TomlNode::Leaf)
            }

            fn visit_f64<E>(self, _: f64) -> Result<TomlNode, E> {
                Ok(TomlNode::Leaf)
            }

            fn visit_str<E>(self, _: &str) -> Result<TomlNode, E> {
                Ok(TomlNode::Leaf)
            }
        }

        // Anything else (a datetime) is no scene value: the scene's own
        // parse refuses it before an index is built.
        deserializer.deserialize_any(NodeVisitor)
    }
}

impl Scene {
    /// Where a key lies, for messages: this scene's file and the key's line.
    pub fn locate(&self, key: &str) -> Location {
        Location {
            file: self.source.name.clone(),
            key: Some(key.to_string()),
            line: self.source.lines.line_of(key),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const TOML: &str = r#"# a scene
[room]
width = 6.0   # m
ceiling = "flat"

[[balloons]]
count = 3

[[balloons]]
count = 4
spawn = { min = [-1.0, 0.0, -1.0], max = [1.0, 1.0, 1.0] }
colors = [
  "red",
  "blue",
]
velocity = [0.0, 0.0, 0.0]

[sim]
dt = 0.01
"#;

    #[test]
    fn toml_values_are_indexed_with_their_lines() {
        let k = KeyLines::from_toml(TOML);
        assert_eq!(k.line_of("room.width"), Some(3));
        assert_eq!(k.line_of("room.ceiling"), Some(4));
        assert_eq!(k.line_of("balloons[0].count"), Some(7));
        assert_eq!(k.line_of("balloons[1].count"), Some(10));
        assert_eq!(k.line_of("balloons[1].spawn.max"), Some(11));
        assert_eq!(k.line_of("balloons[1].colors[1]"), Some(14));
        assert_eq!(k.line_of("balloons[1].velocity"), Some(16));
        assert_eq!(k.line_of("sim.dt"), Some(19));
        // Not in the file: the nearest ancestor.
        assert_eq!(k.line_of("balloons[1].gas"), k.line_of("balloons[1]"));
        assert_eq!(k.line_of("air.temperature_c"), None);
    }

    #[test]
    fn toml_subtable_of_array_element_gets_its_index() {
        let text = "[[balloons]]\ncount = 1\n[[balloons]]\n[balloons.spawn]\nmin = [0, 0, 0]\n";
        let k = KeyLines::from_toml(text);
        assert_eq!(k.line_of("balloons[1].spawn.min"), Some(5));
        assert_eq!(k.line_of("balloons[0].count"), Some(2));
    }

    #[test]
    fn json_values_are_indexed_with_their_lines() {
        let text = "{\n  \"room\": { \"width\": 6 },\n  \"balloons\": [\n    { \"count\": 2 },\n    {\n      \"count\": 5,\n      \"colors\": [\"red\",\n \"blue\"]\n    }\n  ]\n}\n";
        let k = KeyLines::from_json(text);
        assert_eq!(k.line_of("room.width"), Some(2));
        assert_eq!(k.line_of("balloons[0].count"), Some(4));
        assert_eq!(k.line_of("balloons[1]"), Some(5));
        assert_eq!(k.line_of("balloons[1].count"), Some(6));
        assert_eq!(k.line_of("balloons[1].colors[1]"), Some(8));
        assert_eq!(k.line_of("balloons[1].gas"), Some(5));
        // A key escaped in the text is indexed by its value.
        let k = KeyLines::from_json("{\"r\\u006fom\":\n{\"width\": 1}}");
        assert_eq!(k.line_of("room.width"), Some(2));
    }

    #[test]
    fn text_that_does_not_parse_gives_an_empty_index() {
        assert_eq!(KeyLines::from_toml("[room\n"), KeyLines::default());
        assert_eq!(KeyLines::from_json("{\"room\": "), KeyLines::default());
    }

    #[test]
    fn offsets_map_to_lines() {
        assert_eq!(line_of_offset("a\nb\nc", 0), 1);
        assert_eq!(line_of_offset("a\nb\nc", 1), 1);
        assert_eq!(line_of_offset("a\nb\nc", 2), 2);
        assert_eq!(line_of_offset("a\nb\nc", 99), 3);
        assert_eq!(line_of_offset("", 0), 1);
    }

    #[test]
    fn a_long_array_is_indexed_quickly() {
        // 100,000 values on as many lines: quadratic line counting would take minutes.
        let values = vec!["1"; 100_000].join(",\n");
        let text = format!("{{\"balloons\": [{{\"colors\": [\n{values}]}}]}}");
        let started = std::time::Instant::now();
        let k = KeyLines::from_json(&text);
        assert_eq!(k.line_of("balloons[0].colors[99999]"), Some(100_001));
        let toml_text = format!("[[balloons]]\ncolors = [\n{values}]\n");
        let k = KeyLines::from_toml(&toml_text);
        assert_eq!(k.line_of("balloons[0].colors[99999]"), Some(100_002));
        assert!(started.elapsed().as_secs() < 10, "{:?}", started.elapsed());
    }
}
