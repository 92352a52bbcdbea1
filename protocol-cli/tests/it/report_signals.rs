//! `protocol report`'s signals: the series in the page hold the values `protocol decode` prints,
//! at the frames' indices; the default picks the scaled fields of the most frequent commands;
//! `--plot` names select series, and a name that selects nothing is an error that underlines it
//! and offers the spec's closest names; a large capture is decimated with its extremes kept.
//! (The plot drawn in a browser is checked in `cli_report`.)

use crate::support;

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use serde_json::Value;
use support::{json_lines, protocol, text};

/// Runs `report` on `capture` with `args`; the page, or the failed run.
fn report(
    name: &str,
    spec: &str,
    capture: &str,
    args: &[&str],
) -> (std::process::Output, Option<String>) {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("signals");
    std::fs::create_dir_all(&dir).expect("temp dir");
    let page = dir.join(format!("{name}.html"));
    let _ = std::fs::remove_file(&page);
    let mut all = vec!["report", spec, capture, "-o", page.to_str().expect("path")];
    all.extend_from_slice(args);
    let out = protocol(&all, b"");
    (out, std::fs::read_to_string(&page).ok())
}

/// The JSON the page's plotter draws.
fn signal_data(html: &str) -> Value {
    let start = "<script type=\"application/json\" id=\"signal-data\">";
    let from = html.find(start).expect("the signal data") + start.len();
    let to = from + html[from..].find("</script>").expect("its end");
    serde_json::from_str(&html[from..to]).expect("JSON")
}

/// The decoded frames of `decode --format json` (events left out), in order.
fn frames(spec: &str, capture: &str) -> Vec<Value> {
    let out = protocol(&["decode", spec, capture, "--format", "json"], b"");
    assert!(out.status.success(), "{}", text(&out.stderr));
    json_lines(&out.stdout)
        .into_iter()
        .filter(|l| l.get("event").is_none())
        .collect()
}

/// The value at a column's path (`payload.v[2]`) of a frame object.
fn at_path<'v>(frame: &'v Value, path: &str) -> Option<&'v Value> {
    let mut v = frame;
    for part in path.split('.') {
        let (name, index) = match part.split_once('[') {
            Some((n, i)) => (n, i.trim_end_matches(']').parse::<usize>().ok()),
            None => (part, None),
        };
        v = v.get(name)?;
        if let Some(i) = index {
            v = v.get(i)?;
        }
    }
    Some(v)
}

/// Every point of every series is the value `decode` prints for that frame, and every frame of
/// the series' command with that column is a point (no decimation at this size).
fn assert_series_are_decode(data: &Value, frames: &[Value]) -> usize {
    let mut points = 0;
    for s in data["series"].as_array().expect("series") {
        let name = s["name"].as_str().expect("name");
        let (command, path) = name.split_once('.').expect("COMMAND.path");
        let want: Vec<(u64, f64)> = frames
            .iter()
            .enumerate()
            .filter(|(_, f)| f["command"] == command)
            .filter_map(|(i, f)| Some((i as u64, at_path(f, path)?.as_f64()?)))
            .collect();
        let xs: Vec<u64> = s["x"]
            .as_array()
            .expect("x")
            .iter()
            .filter_map(Value::as_u64)
            .collect();
        let ys: Vec<f64> = s["y"]
            .as_array()
            .expect("y")
            .iter()
            .filter_map(Value::as_f64)
            .collect();
        let got: Vec<(u64, f64)> = xs.into_iter().zip(ys).collect();
        assert_eq!(got, want, "{name}: the page's points and decode's values");
        assert_eq!(s["samples"], want.len(), "{name}");
        points += got.len();
    }
    points
}

#[test]
fn the_default_plots_the_scaled_fields_of_the_most_frequent_commands() {
    let (spec, capture) = ("specs/hflink.toml", "examples/captures/hflink.bin");
    let (out, html) = report("default", spec, capture, &[]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let html = html.expect("the page");
    let data = signal_data(&html);
    let frames = frames(spec, capture);
    let points = assert_series_are_decode(&data, &frames);
    let series = data["series"].as_array().expect("series");
    assert_eq!(series.len(), 6, "the default's bound");
    assert!(points > 200, "{points} points");

    // The commands plotted are the most frequent ones that have fields with a unit (HFLink's
    // fields have units and no scale); the panels are their units.
    let mut counts: BTreeMap<&str, usize> = BTreeMap::new();
    for f in &frames {
        *counts
            .entry(f["command"].as_str().unwrap_or(""))
            .or_default() += 1;
    }
    for s in series {
        let command = s["name"]
            .as_str()
            .expect("name")
            .split('.')
            .next()
            .expect("command");
        let n = counts[command];
        assert!(
            counts.values().filter(|m| **m > n).count() < 2,
            "{command} ({n} frames) is among the two most frequent commands: {counts:?}"
        );
        assert!(!s["unit"].as_str().expect("unit").is_empty(), "{s}");
    }
    let units: Vec<&str> = data["panels"]
        .as_array()
        .expect("panels")
        .iter()
        .map(|p| p["unit"].as_str().expect("unit"))
        .collect();
    assert_eq!(units, ["m or m/s", "rad or rad/s"]);
    assert!(html.contains("Not plotted (at most 6 series by default): READ_GLOBAL_COORDINATE"));
    assert!(!html.contains("id=\"decimated\""), "nothing to decimate");
}

#[test]
fn plot_names_select_series() {
    let (spec, capture) = ("specs/hflink.toml", "examples/captures/hflink.bin");
    let args = [
        "--plot",
        "payload.z, READ_SYSTEM_INFO.payload.cpu_temperature",
        "--plot",
        "READ_SYSTEM_INFO.header.sender",
    ];
    let (out, html) = report("chosen", spec, capture, &args);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let data = signal_data(&html.expect("the page"));
    let names: Vec<&str> = data["series"]
        .as_array()
        .expect("series")
        .iter()
        .map(|s| s["name"].as_str().expect("name"))
        .collect();
    // `payload.z` is every command's `z`, in order of first appearance; then the others in the
    // order given.
    assert_eq!(
        names,
        [
            "SHAKING_HANDS.payload.z",
            "SET_ROBOT_SPEED.payload.z",
            "READ_ROBOT_SPEED.payload.z",
            "READ_GLOBAL_COORDINATE.payload.z",
            "READ_SYSTEM_INFO.payload.cpu_temperature",
            "READ_SYSTEM_INFO.header.sender",
        ]
    );
    assert_series_are_decode(&data, &frames(spec, capture));
    let temperature = &data["series"][4];
    assert_eq!(temperature["unit"], "°C");
    assert_eq!(
        temperature["samples"], 2,
        "the responses carry it, not the requests"
    );
}

/// Stderr with miette's frame undone: one line, single spaces.
fn message(out: &std::process::Output) -> String {
    text(&out.stderr)
        .replace(['│', '·', '╭', '╰', '─', '┬'], " ")
        .split_whitespace()
        .collect::<Vec<_>>()
        .join(" ")
}

#[test]
fn a_name_that_selects_nothing_is_underlined_with_the_closest_names() {
    let (spec, capture) = ("specs/hflink.toml", "examples/captures/hflink.bin");
    let arg = "payload.x,payload.cpu_temprature,SET_ROBOT_SPEED.payload.q";
    let (out, html) = report("unknown", spec, capture, &["--plot", arg]);
    assert!(!out.status.success());
    assert!(html.is_none(), "no page for a bad name");
    let raw = text(&out.stderr);
    // The argument is quoted with each bad name underlined from its first character.
    let line = raw
        .lines()
        .find(|l| l.contains(arg))
        .expect("the argument quoted");
    let under = raw
        .lines()
        .skip_while(|l| !l.contains(arg))
        .nth(1)
        .expect("the underline");
    let column = |s: &str, c: char| s.char_indices().position(|(_, x)| x == c);
    let arg_at = line.find(arg).expect("arg");
    let first = column(under, '─').expect("an underline");
    assert_eq!(
        under.chars().skip(first).take_while(|c| *c != ' ').count(),
        "payload.cpu_temprature".len(),
        "{raw}"
    );
    assert_eq!(
        first,
        line[..arg_at].chars().count() + "payload.x,".len(),
        "{raw}"
    );
    let m = message(&out);
    assert!(m.contains("no such field"), "{m}");
    assert!(
        m.contains("`payload.cpu_temprature`: did you mean payload.cpu_temperature?"),
        "{m}"
    );
    assert!(
        m.contains("`SET_ROBOT_SPEED.payload.q`: did you mean SET_ROBOT_SPEED.payload.x"),
        "{m}"
    );
    assert!(
        !m.contains("`payload.x`"),
        "a good name is not refused: {m}"
    );

    // A field that holds names, not numbers.
    let (out, _) = report(
        "named",
        "specs/scout.toml",
        "examples/captures/scout.bin",
        &["--frame", "uart", "--plot", "payload.control_mode"],
    );
    assert!(!out.status.success());
    let m = message(&out);
    assert!(m.contains("names or text, not numbers"), "{m}");
}

#[test]
fn a_large_capture_is_decimated_with_its_extremes() {
    let one = std::fs::read(support::root().join("examples/captures/hflink.bin")).expect("capture");
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("signals");
    std::fs::create_dir_all(&dir).expect("dir");
    let big = dir.join("hflink-x120.bin");
    std::fs::write(&big, one.repeat(120)).expect("capture");
    let big = big.to_str().expect("path");
    let spec = "specs/hflink.toml";
    let arg = "READ_ROBOT_SPEED.payload.x";
    let (out, html) = report("large", spec, big, &["--plot", arg]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let html = html.expect("the page");
    let data = signal_data(&html);
    let s = &data["series"][0];
    let want: Vec<(u64, f64)> = frames(spec, big)
        .iter()
        .enumerate()
        .filter(|(_, f)| f["command"] == "READ_ROBOT_SPEED")
        .filter_map(|(i, f)| Some((i as u64, f["payload"]["x"].as_f64()?)))
        .collect();
    let xs: Vec<u64> = s["x"]
        .as_array()
        .expect("x")
        .iter()
        .filter_map(Value::as_u64)
        .collect();
    let ys: Vec<f64> = s["y"]
        .as_array()
        .expect("y")
        .iter()
        .filter_map(Value::as_f64)
        .collect();
    assert_eq!(s["samples"], want.len());
    assert!(want.len() > 4000, "{} values", want.len());
    assert!(xs.len() <= 3000, "{} points in the page", xs.len());
    // Every point is a sample of the capture, in order, and the extremes are among them.
    let got: Vec<(u64, f64)> = xs.into_iter().zip(ys).collect();
    assert!(got.iter().all(|p| want.contains(p)), "points are samples");
    assert!(got.windows(2).all(|w| w[0].0 < w[1].0), "in order");
    let max = |v: &[(u64, f64)]| v.iter().map(|p| p.1).fold(f64::MIN, f64::max);
    let min = |v: &[(u64, f64)]| v.iter().map(|p| p.1).fold(f64::MAX, f64::min);
    assert_eq!((min(&got), max(&got)), (min(&want), max(&want)));
    assert!(html.contains(&format!(
        "id=\"decimated\">Decimated: {arg} ({} values)",
        want.len()
    )));
}
