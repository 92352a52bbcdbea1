//! Shrinking a failing spec to a smaller one that still fails: whole tables (structs, enums,
//! frame formats, directions), single lines (commands, fields, layout elements, a format's
//! keys), the keys of an inline table (a scale, a byte order, a counter, a check's table), and
//! field types simplified to `u8`. A candidate is kept when `fails` says it still fails; the
//! caller's `fails` also rejects a spec the front end refuses, so every step stays valid.
//!
//! It works on the spec's text, line by line, as the random generator writes it (one field,
//! element or command a line), so it shrinks any spec written that way, from any failure: a
//! disagreement between backends, a panic, an allocation. Plain `std`, no dependencies.
#![allow(dead_code)]

/// The smallest spec this finds from `text` for which `fails` holds, trying at most `budget`
/// candidates. `fails(text)` must hold.
pub fn shrink(text: &str, budget: usize, mut fails: impl FnMut(&str) -> bool) -> String {
    let mut best: Vec<String> = text.lines().map(str::to_string).collect();
    let mut tries = 0;
    let mut changed = true;
    while changed && tries < budget {
        changed = false;
        for pass in [tables, lines, keys, types] {
            for candidate in pass(&best) {
                if tries >= budget {
                    break;
                }
                tries += 1;
                if fails(&join(&candidate)) {
                    best = candidate;
                    changed = true;
                    // The candidates were of the old text: draw them again.
                    break;
                }
            }
        }
    }
    join(&best)
}

fn join(lines: &[String]) -> String {
    let mut t = lines.join("\n");
    t.push('\n');
    t
}

/// The spec without one of its tables (a `[section]` line up to the next), `[protocol]` kept.
fn tables(lines: &[String]) -> Vec<Vec<String>> {
    let starts: Vec<usize> = (0..lines.len())
        .filter(|&i| lines[i].starts_with('[') && lines[i] != "[protocol]")
        .collect();
    starts
        .iter()
        .rev()
        .map(|&s| {
            let end = (s + 1..lines.len())
                .find(|&i| lines[i].starts_with('['))
                .unwrap_or(lines.len());
            let mut out = lines[..s].to_vec();
            out.extend_from_slice(&lines[end..]);
            out
        })
        .collect()
}

/// The spec without one of its lines (not a table's header, nor an array's brackets).
fn lines(lines: &[String]) -> Vec<Vec<String>> {
    (0..lines.len())
        .rev()
        .filter(|&i| {
            let l = lines[i].trim();
            !(l.is_empty()
                || l.starts_with('[')
                || l.ends_with('[')
                || l == "]"
                || l.starts_with('#'))
        })
        .map(|i| {
            let mut out = lines.to_vec();
            out.remove(i);
            out
        })
        .collect()
}

/// The spec with one `key = value` of a line's inline table dropped (the first, the name or
/// kind, kept).
fn keys(lines: &[String]) -> Vec<Vec<String>> {
    let mut out = Vec::new();
    for (i, line) in lines.iter().enumerate() {
        let parts = top_level_parts(line);
        for k in (1..parts.len()).rev() {
            let (from, to) = parts[k];
            let mut shorter = line.clone();
            shorter.replace_range(from..to, "");
            let mut candidate = lines.to_vec();
            candidate[i] = shorter;
            out.push(candidate);
        }
    }
    out
}

/// The spans of `, key = value` after the first pair of a line's outermost inline table.
pub fn top_level_parts(line: &str) -> Vec<(usize, usize)> {
    let Some(open) = line.find('{') else {
        return Vec::new();
    };
    let mut depth = 0;
    let mut quoted = false;
    let mut commas = Vec::new();
    let mut close = None;
    for (i, c) in line.char_indices().skip_while(|&(i, _)| i < open) {
        match c {
            '"' => quoted = !quoted,
            _ if quoted => {}
            '{' | '[' => depth += 1,
            '}' | ']' => {
                depth -= 1;
                if depth == 0 {
                    close = Some(i);
                    break;
                }
            }
            ',' if depth == 1 => commas.push(i),
            _ => {}
        }
    }
    let Some(close) = close else {
        return Vec::new();
    };
    let mut ends: Vec<usize> = commas.clone();
    ends.push(close);
    let mut parts = vec![(open + 1, ends[0])];
    for w in 0..commas.len() {
        // From the comma to the next comma (or to the space before the brace).
        let to = if w + 1 < commas.len() {
            commas[w + 1]
        } else {
            line[..close].trim_end().len()
        };
        parts.push((commas[w], to));
    }
    parts
}

/// The spec with one field's type simplified to `u8`.
fn types(lines: &[String]) -> Vec<Vec<String>> {
    let mut out = Vec::new();
    for (i, line) in lines.iter().enumerate() {
        let Some(at) = line.find("type = \"") else {
            continue;
        };
        let start = at + "type = \"".len();
        let Some(len) = line[start..].find('"') else {
            continue;
        };
        if &line[start..start + len] == "u8" {
            continue;
        }
        let mut simpler = line.clone();
        simpler.replace_range(start..start + len, "u8");
        let mut candidate = lines.to_vec();
        candidate[i] = simpler;
        out.push(candidate);
    }
    out
}
