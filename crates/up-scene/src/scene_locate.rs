//! Which key sits on which line of a scene file.
//!
//! serde reports where a TOML or JSON error is (a byte span or a line) but not
//! the key path, and validation knows the key path but not the line. A light
//! scan of the text records every key path with the line it starts on, which
//! answers both questions. The scan is forgiving: it never fails, it only ever
//! makes messages more precise.

/// Key paths (`room.width`, `balloons[1].spawn.min`) with their 1-based lines, in file order.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct KeyLines {
    entries: Vec<(String, usize)>,
}

impl KeyLines {
    /// The line of `path`, or of its nearest ancestor present in the file
    /// (a defaulted `balloons[0].count` points at the `[[balloons]]` header).
    pub fn line_of(&self, path: &str) -> Option<usize> {
        let mut probe = path;
        loop {
            if let Some((_, line)) = self.entries.iter().find(|(p, _)| p == probe) {
                return Some(*line);
            }
            let cut = probe.rfind(['.', '['])?;
            probe = &probe[..cut];
        }
    }

    /// The key path written on `line`, or the last one before it.
    pub fn key_at(&self, line: usize) -> Option<&str> {
        let on_line = self.entries.iter().rev().find(|(_, l)| *l == line);
        on_line
            .or_else(|| self.entries.iter().rev().find(|(_, l)| *l <= line))
            .map(|(p, _)| p.as_str())
    }

    fn push(&mut self, path: String, line: usize) {
        if !path.is_empty() {
            self.entries.push((path, line));
        }
    }

    /// Indexes a TOML document: table headers, `key = value` lines and the
    /// keys of inline tables.
    pub fn scan_toml(text: &str) -> Self {
        let mut out = KeyLines::default();
        // Array-of-tables names and how many elements each has so far.
        let mut array_tables: Vec<(String, usize)> = Vec::new();
        let mut table = String::new();
        // Open `[` of a multi-line array value: its lines hold no keys or headers.
        let mut value_depth = 0i32;
        for (i, raw) in text.lines().enumerate() {
            let line = i + 1;
            let s = strip_toml_comment(raw).trim();
            if s.is_empty() {
                continue;
            }
            if value_depth > 0 {
                value_depth += bracket_balance(s);
                continue;
            }
            if let Some(name) = s.strip_prefix("[[").and_then(|r| r.split("]]").next()) {
                let name = unquote_dotted(name);
                let count = match array_tables.iter_mut().find(|(n, _)| *n == name) {
                    Some(entry) => {
                        entry.1 += 1;
                        entry.1
                    }
                    None => {
                        array_tables.push((name.clone(), 1));
                        1
                    }
                };
                table = resolve_table(&name, &array_tables, Some(count - 1));
                out.push(table.clone(), line);
            } else if let Some(name) = s.strip_prefix('[').and_then(|r| r.split(']').next()) {
                table = resolve_table(&unquote_dotted(name), &array_tables, None);
                out.push(table.clone(), line);
            } else if let Some((key, value)) = split_key_value(s) {
                let path = join(&table, &key);
                out.push(path.clone(), line);
                let value = value.trim_start();
                if value.starts_with('{') {
                    for inner in inline_table_keys(value) {
                        out.push(join(&path, &inner), line);
                    }
                }
                value_depth = bracket_balance(value).max(0);
            }
        }
        out
    }

    /// Indexes a JSON document: every object key and every array element that
    /// is an object or array.
    pub fn scan_json(text: &str) -> Self {
        enum Frame {
            Object {
                key: Option<String>,
                expecting_key: bool,
            },
            Array {
                index: usize,
            },
        }
        fn path_of(stack: &[Frame]) -> String {
            let mut path = String::new();
            for frame in stack {
                match frame {
                    Frame::Object { key: Some(k), .. } => {
                        if !path.is_empty() {
                            path.push('.');
                        }
                        path.push_str(k);
                    }
                    Frame::Object { key: None, .. } => {}
                    Frame::Array { index } => path.push_str(&format!("[{index}]")),
                }
            }
            path
        }
        let mut out = KeyLines::default();
        let mut stack: Vec<Frame> = Vec::new();
        let mut line = 1;
        let mut chars = text.chars();
        while let Some(c) = chars.next() {
            match c {
                '\n' => line += 1,
                '"' => {
                    let mut s = String::new();
                    while let Some(c) = chars.next() {
                        match c {
                            '"' => break,
                            '\\' => {
                                if let Some(escaped) = chars.next() {
                                    s.push(escaped);
                                }
                            }
                            '\n' => line += 1,
                            c => s.push(c),
                        }
                    }
                    if let Some(Frame::Object {
                        key,
                        expecting_key: true,
                    }) = stack.last_mut()
                    {
                        *key = Some(s);
                        out.push(path_of(&stack), line);
                    }
                }
                ':' => {
                    if let Some(Frame::Object { expecting_key, .. }) = stack.last_mut() {
                        *expecting_key = false;
                    }
                }
                ',' => match stack.last_mut() {
                    Some(Frame::Object { expecting_key, .. }) => *expecting_key = true,
                    Some(Frame::Array { index }) => *index += 1,
                    None => {}
                },
                '{' | '[' => {
                    if let Some(Frame::Array { .. }) = stack.last() {
                        out.push(path_of(&stack), line);
                    }
                    stack.push(if c == '{' {
                        Frame::Object {
                            key: None,
                            expecting_key: true,
                        }
                    } else {
                        Frame::Array { index: 0 }
                    });
                }
                '}' | ']' => {
                    stack.pop();
                }
                _ => {}
            }
        }
        out
    }
}

/// 1-based line of a byte offset.
pub fn line_of_offset(text: &str, offset: usize) -> usize {
    let end = offset.min(text.len());
    text.as_bytes()[..end]
        .iter()
        .filter(|&&b| b == b'\n')
        .count()
        + 1
}

fn join(table: &str, key: &str) -> String {
    if table.is_empty() {
        key.to_string()
    } else {
        format!("{table}.{key}")
    }
}

/// `balloons.spawn` after two `[[balloons]]` headers is `balloons[1].spawn`.
fn resolve_table(name: &str, array_tables: &[(String, usize)], own_index: Option<usize>) -> String {
    let mut path = String::new();
    let mut prefix = String::new();
    let parts: Vec<&str> = name.split('.').collect();
    for (i, part) in parts.iter().enumerate() {
        prefix = join(&prefix, part);
        path = join(&path, part);
        let is_last = i + 1 == parts.len();
        let index = if is_last {
            own_index
        } else {
            array_tables
                .iter()
                .find(|(n, _)| *n == prefix)
                .map(|(_, count)| count - 1)
        };
        if let Some(index) = index {
            path.push_str(&format!("[{index}]"));
        }
    }
    path
}

fn unquote_dotted(name: &str) -> String {
    name.split('.')
        .map(|p| p.trim().trim_matches('"'))
        .collect::<Vec<_>>()
        .join(".")
}

/// `key = value` → (key, value), with the key unquoted; `None` for anything else.
fn split_key_value(s: &str) -> Option<(String, &str)> {
    let eq = s.find('=')?;
    let key = s[..eq].trim();
    let plain = |c: char| c.is_ascii_alphanumeric() || matches!(c, '_' | '-' | '.' | '"' | ' ');
    if key.is_empty() || !key.chars().all(plain) {
        return None;
    }
    Some((unquote_dotted(key), &s[eq + 1..]))
}

/// Keys at the top level of an inline table `{ min = [..], max = [..] }`.
fn inline_table_keys(value: &str) -> Vec<String> {
    let mut keys = Vec::new();
    let mut depth = 0i32;
    let mut in_string = false;
    let mut start = None;
    for (i, c) in value.char_indices() {
        if in_string {
            in_string = c != '"';
            continue;
        }
        match c {
            '"' if start.is_none() => in_string = true,
            '{' | '[' => {
                depth += 1;
                if depth == 1 && c == '{' {
                    start = Some(i + 1);
                }
            }
            '}' | ']' => depth -= 1,
            ',' if depth == 1 => start = Some(i + 1),
            '=' if depth == 1 => {
                if let Some(from) = start.take() {
                    let key = value[from..i].trim().trim_matches('"');
                    if !key.is_empty() {
                        keys.push(key.to_string());
                    }
                }
            }
            _ => {}
        }
    }
    keys
}

/// Net count of `[`/`{` opened minus closed, outside strings.
fn bracket_balance(s: &str) -> i32 {
    let mut depth = 0;
    let mut in_string = false;
    for c in s.chars() {
        match c {
            '"' => in_string = !in_string,
            '[' | '{' if !in_string => depth += 1,
            ']' | '}' if !in_string => depth -= 1,
            _ => {}
        }
    }
    depth
}

fn strip_toml_comment(line: &str) -> &str {
    let mut in_string = false;
    for (i, c) in line.char_indices() {
        match c {
            '"' => in_string = !in_string,
            '#' if !in_string => return &line[..i],
            _ => {}
        }
    }
    line
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
    fn toml_keys_are_indexed_with_their_lines() {
        let k = KeyLines::scan_toml(TOML);
        assert_eq!(k.line_of("room.width"), Some(3));
        assert_eq!(k.line_of("balloons[0].count"), Some(7));
        assert_eq!(k.line_of("balloons[1].count"), Some(10));
        assert_eq!(k.line_of("balloons[1].spawn.max"), Some(11));
        assert_eq!(k.line_of("balloons[1].velocity"), Some(16));
        assert_eq!(k.line_of("sim.dt"), Some(19));
        // Not in the file: the nearest ancestor.
        assert_eq!(k.line_of("balloons[0].gas"), Some(6));
        assert_eq!(k.line_of("air.temperature_c"), None);
    }

    #[test]
    fn toml_line_gives_the_key_written_there() {
        let k = KeyLines::scan_toml(TOML);
        assert_eq!(k.key_at(10), Some("balloons[1].count"));
        assert_eq!(k.key_at(13), Some("balloons[1].colors"));
        assert_eq!(k.key_at(4), Some("room.ceiling"));
    }

    #[test]
    fn toml_subtable_of_array_element_gets_its_index() {
        let text = "[[balloons]]\ncount = 1\n[[balloons]]\n[balloons.spawn]\nmin = [0, 0, 0]\n";
        let k = KeyLines::scan_toml(text);
        assert_eq!(k.line_of("balloons[1].spawn.min"), Some(5));
    }

    #[test]
    fn json_keys_are_indexed_with_their_lines() {
        let text = "{\n  \"room\": { \"width\": 6 },\n  \"balloons\": [\n    { \"count\": 2 },\n    {\n      \"count\": 5\n    }\n  ]\n}\n";
        let k = KeyLines::scan_json(text);
        assert_eq!(k.line_of("room.width"), Some(2));
        assert_eq!(k.line_of("balloons[0].count"), Some(4));
        assert_eq!(k.line_of("balloons[1].count"), Some(6));
        assert_eq!(k.key_at(6), Some("balloons[1].count"));
    }

    #[test]
    fn offsets_map_to_lines() {
        assert_eq!(line_of_offset("a\nb\nc", 0), 1);
        assert_eq!(line_of_offset("a\nb\nc", 2), 2);
        assert_eq!(line_of_offset("a\nb\nc", 99), 3);
    }
}
