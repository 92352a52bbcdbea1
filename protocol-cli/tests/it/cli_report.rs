//! `protocol report`: the page is self-contained and holds every item of the capture, and it
//! renders in a real headless Chromium (the DOM after its script ran, and a screenshot).
//!
//! The browser test needs `chromium` (or the browser named by `PROTOCOL_CHROMIUM`). Without
//! one it says so and checks nothing more, unless `PROTOCOL_REQUIRE_BROWSER` is set, as CI
//! sets it: then a missing browser fails the test.

use crate::support;

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;

use support::{json_lines, protocol, text};

/// A report of the HFLink capture, written under the test's temporary directory.
fn report(name: &str) -> (PathBuf, String) {
    report_with(name, &[])
}

/// A report of the HFLink capture with more arguments.
fn report_with(name: &str, more: &[&str]) -> (PathBuf, String) {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    std::fs::create_dir_all(&dir).expect("temp dir");
    let path = dir.join("report.html");
    let mut args = vec![
        "report",
        "specs/hflink.toml",
        "examples/captures/hflink.bin",
        "-o",
        path.to_str().expect("path"),
    ];
    args.extend_from_slice(more);
    let out = protocol(&args, b"");
    assert!(out.status.success(), "{}", text(&out.stderr));
    let html = std::fs::read_to_string(&path).expect("the report");
    (path, html)
}

#[test]
fn the_page_is_self_contained_and_holds_every_item() {
    let (_, html) = report("items");
    for external in ["<link", " src=", " href=", "@import", "url("] {
        assert!(
            !html.contains(external),
            "the page loads something: `{external}`"
        );
    }
    // Every frame, rejected candidate and skipped run of `decode` is a block of the hex view.
    let out = protocol(
        &[
            "decode",
            "specs/hflink.toml",
            "examples/captures/hflink.bin",
            "--format",
            "json",
        ],
        b"",
    );
    let lines = json_lines(&out.stdout);
    let count =
        |pred: &dyn Fn(&serde_json::Value) -> bool| lines.iter().filter(|l| pred(l)).count();
    let frames = count(&|l| {
        l.get("event").is_none()
            || ["unknown_command", "unknown_direction", "bad_payload"]
                .contains(&l["event"].as_str().unwrap_or(""))
    });
    let skipped = count(&|l| l["event"] == "skipped");
    let rejected = lines.len() - frames - skipped;
    assert_eq!(html.matches("<div class=\"frame").count(), frames);
    assert_eq!(html.matches("<div class=\"skipped\"").count(), skipped);
    assert_eq!(html.matches("<div class=\"rejected\"").count(), rejected);
    assert!(
        html.contains("<div class=\"frame bad\""),
        "the unknown command is highlighted"
    );
    assert!(
        html.contains("data-name=\"cpu_temperature\""),
        "payload fields are named"
    );
    assert!(
        html.contains("class=\"bar check\""),
        "the chart shows the bad checks"
    );
}

fn browser() -> Option<PathBuf> {
    if let Some(path) = std::env::var_os("PROTOCOL_CHROMIUM") {
        return Some(path.into());
    }
    let path = std::env::var_os("PATH")?;
    std::env::split_paths(&path)
        .flat_map(|d| ["chromium", "chromium-browser"].map(|n| d.join(n)))
        .find(|p| p.is_file())
}

/// Runs the browser headless on `page` with `args`, in a fresh profile.
fn headless(browser: &Path, page: &Path, profile: &Path, args: &[&str]) -> std::process::Output {
    Command::new(browser)
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--no-first-run",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
        ])
        .arg(format!("--user-data-dir={}", profile.display()))
        .args(args)
        .arg(format!("file://{}", page.display()))
        .output()
        .expect("the browser runs")
}

#[test]
fn the_page_renders_in_a_headless_chromium() {
    let Some(browser) = browser() else {
        assert!(
            std::env::var_os("PROTOCOL_REQUIRE_BROWSER").is_none(),
            "PROTOCOL_REQUIRE_BROWSER is set and no chromium is on the PATH"
        );
        eprintln!("no chromium on the PATH: the report is not checked in a browser");
        return;
    };
    let (page, _) = report("browser");
    let dir = page.parent().expect("dir").to_path_buf();

    let dom = headless(&browser, &page, &dir.join("profile-dom"), &["--dump-dom"]);
    assert!(dom.status.success(), "{}", text(&dom.stderr));
    let dom = text(&dom.stdout);
    assert!(
        dom.contains("data-ready=\"1\""),
        "the page's script ran without an error"
    );
    assert!(dom.contains("<table id=\"stats\">") && dom.contains("checksum failures"));
    assert!(dom.contains("<tr data-command=\"SET_ROBOT_SPEED\">"));
    assert!(dom.contains("<svg id=\"quality\""));
    assert!(
        dom.matches("class=\"field\"").count() > 1000,
        "fields are outlined"
    );

    let shot = dir.join("report.png");
    let _ = std::fs::remove_file(&shot);
    let out = headless(
        &browser,
        &page,
        &dir.join("profile-shot"),
        &[
            &format!("--screenshot={}", shot.display()),
            "--window-size=1280,1400",
        ],
    );
    assert!(out.status.success(), "{}", text(&out.stderr));
    let png = std::fs::read(&shot).expect("a screenshot");
    assert_eq!(png.get(..8), Some(&b"\x89PNG\r\n\x1a\n"[..]), "a PNG");
    let be32 = |at: usize| u32::from_be_bytes(png[at..at + 4].try_into().expect("4 bytes"));
    assert_eq!((be32(16), be32(20)), (1280, 1400), "the window's size");
    assert!(
        png.len() > 20_000,
        "a page, not a blank window: {} bytes",
        png.len()
    );
}

/// `report --direction NAME`, as `decode --direction` has it, on `specs/dynamixel1.toml` (whose
/// instruction and status packets share one layout): the direction picks how the frames decode;
/// it is required for such a spec and refused for a spec whose header tells its directions.
#[test]
fn the_direction_picks_how_frames_decode() {
    let path = support::root().join("tests/vectors/dynamixel_protocol1.json");
    let vectors: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(path).expect("vectors")).expect("JSON");
    let frames = vectors["frames"].as_array().expect("frames");
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("direction");
    std::fs::create_dir_all(&dir).expect("temp dir");
    let page = |kind: &str, args: &[&str]| {
        let of_kind: Vec<&serde_json::Value> =
            frames.iter().filter(|f| f["packet"] == kind).collect();
        let bytes: Vec<u8> = of_kind
            .iter()
            .flat_map(|f| support::unhex(f["hex"].as_str().expect("hex")))
            .collect();
        let capture = dir.join(format!("{kind}.bin"));
        std::fs::write(&capture, bytes).expect("capture");
        let html = dir.join(format!("{kind}.html"));
        let _ = std::fs::remove_file(&html);
        let mut all = vec![
            "report",
            "specs/dynamixel1.toml",
            capture.to_str().expect("path"),
            "-o",
            html.to_str().expect("path"),
        ];
        all.extend_from_slice(args);
        let out = protocol(&all, b"");
        let page = std::fs::read_to_string(&html).ok();
        (out, page, of_kind)
    };

    let (out, html, requests) = page("instruction", &["--direction", "request"]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let html = html.expect("the report");
    assert_eq!(
        html.matches("<div class=\"frame\"").count(),
        requests.len(),
        "every instruction packet decodes as a request"
    );
    assert!(!html.contains("<div class=\"frame bad\""));
    for command in ["PING", "WRITE", "SYNC_WRITE"] {
        assert!(
            html.contains(&format!("data-command=\"{command}\"")),
            "{command} is named"
        );
    }

    let (out, html, statuses) = page("status", &["--direction", "response"]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let html = html.expect("the report");
    assert_eq!(
        html.matches("<div class=\"frame\"").count(),
        statuses.len(),
        "every status packet decodes as a response"
    );
    assert_eq!(
        html.matches("data-command=\"(Status)\"").count(),
        statuses.len(),
        "a status packet is labelled by the struct it carries"
    );
    assert!(html.contains("overload"), "the status fields are named");

    // Without a direction, the spec's directions are named and no page is written.
    let (out, html, _) = page("status", &[]);
    assert!(!out.status.success());
    assert!(message(&out).contains("--direction"), "{}", message(&out));
    assert!(html.is_none(), "no page without a direction");

    // A direction the spec lacks is refused; so is one for a spec whose header tells them.
    let (out, _, _) = page("status", &["--direction", "sideways"]);
    assert!(!out.status.success());
    assert!(
        message(&out).contains("no such direction"),
        "{}",
        message(&out)
    );
    let html = dir.join("hflink.html");
    let out = protocol(
        &[
            "report",
            "specs/hflink.toml",
            "examples/captures/hflink.bin",
            "-o",
            html.to_str().expect("path"),
            "--direction",
            "request",
        ],
        b"",
    );
    assert!(!out.status.success());
    assert!(message(&out).contains("header field"), "{}", message(&out));
}

/// Stderr with miette's wrapping undone: one line, single spaces.
fn message(out: &std::process::Output) -> String {
    text(&out.stderr)
        .replace('│', " ")
        .split_whitespace()
        .collect::<Vec<_>>()
        .join(" ")
}

/// The attributes of the first tag `<NAME ...>` at or after `from` in `html`.
fn tag_attrs(html: &str, name: &str, from: usize) -> Option<(usize, BTreeMap<String, String>)> {
    let start = from + html[from..].find(&format!("<{name} "))?;
    let end = start + html[start..].find('>')?;
    let mut attrs = BTreeMap::new();
    let mut rest = &html[start + name.len() + 2..end];
    while let Some(eq) = rest.find("=\"") {
        let key = rest[..eq].trim().to_string();
        let close = rest[eq + 2..].find('"')? + eq + 2;
        attrs.insert(key, rest[eq + 2..close].to_string());
        rest = &rest[close + 1..];
    }
    Some((end, attrs))
}

/// The JSON the page's plotter draws.
fn signal_data(html: &str) -> serde_json::Value {
    let start = "<script type=\"application/json\" id=\"signal-data\">";
    let from = html.find(start).expect("the signal data") + start.len();
    let to = from + html[from..].find("</script>").expect("its end");
    serde_json::from_str(&html[from..to]).expect("JSON")
}

/// A screenshot as RGB rows.
struct Shot {
    width: usize,
    height: usize,
    rgb: Vec<u8>,
}

impl Shot {
    fn read(path: &Path) -> Shot {
        let file = std::fs::File::open(path).expect("the screenshot");
        let mut decoder = png::Decoder::new(std::io::BufReader::new(file));
        decoder.set_transformations(png::Transformations::EXPAND | png::Transformations::STRIP_16);
        let mut reader = decoder.read_info().expect("a PNG");
        let mut buf = vec![0; reader.output_buffer_size()];
        let info = reader.next_frame(&mut buf).expect("its pixels");
        let channels = info.color_type.samples();
        assert!(channels >= 3, "a colour screenshot: {:?}", info.color_type);
        let rgb = buf[..info.buffer_size()]
            .chunks(channels)
            .flat_map(|p| [p[0], p[1], p[2]])
            .collect();
        Shot {
            width: info.width as usize,
            height: info.height as usize,
            rgb,
        }
    }

    fn pixel(&self, x: i64, y: i64) -> Option<[u8; 3]> {
        let (x, y) = (usize::try_from(x).ok()?, usize::try_from(y).ok()?);
        if x >= self.width || y >= self.height {
            return None;
        }
        let at = 3 * (y * self.width + x);
        Some([self.rgb[at], self.rgb[at + 1], self.rgb[at + 2]])
    }

    /// Whether a pixel within `radius` of (x, y) is `colour`, to an anti-aliasing tolerance.
    fn near(&self, x: f64, y: f64, radius: i64, colour: [u8; 3]) -> bool {
        let (cx, cy) = (x.round() as i64, y.round() as i64);
        (-radius..=radius).any(|dy| {
            (-radius..=radius).any(|dx| {
                self.pixel(cx + dx, cy + dy).is_some_and(|p| {
                    p.iter()
                        .zip(colour)
                        .map(|(a, b)| a.abs_diff(b) as u32)
                        .sum::<u32>()
                        <= 60
                })
            })
        })
    }
}

fn rgb(hex: &str) -> [u8; 3] {
    let n = u32::from_str_radix(hex.trim_start_matches('#'), 16).expect("#rrggbb");
    [(n >> 16) as u8, (n >> 8) as u8, n as u8]
}

/// Distance from point p to the segment a-b.
fn to_segment(p: (f64, f64), a: (f64, f64), b: (f64, f64)) -> f64 {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let len = dx * dx + dy * dy;
    let t = if len == 0.0 {
        0.0
    } else {
        (((p.0 - a.0) * dx + (p.1 - a.1) * dy) / len).clamp(0.0, 1.0)
    };
    (p.0 - a.0 - t * dx).hypot(p.1 - a.1 - t * dy)
}

/// The signals the browser test plots (and docs/report-signals.png shows): two panels, each
/// with a series that crosses the other in a few places only.
const PLOTTED: &str = "READ_ROBOT_SPEED.payload.x,READ_GLOBAL_COORDINATE.payload.x,\
READ_ROBOT_SPEED.payload.z,READ_GLOBAL_COORDINATE.payload.z";

/// The signal plot of a report in a real browser. The DOM after the script ran: the
/// plotter recorded no error and no failed check, and drew every series. The screenshot: at
/// the place of each sample (computed here from the page's data and the plot area's place and
/// range, which the plotter records on each canvas), a pixel of the series' colour, wherever
/// no series drawn later passes; and most of each plot area is still background. A copy of
/// the page whose plotter throws must show its error in the DOM. (Colours at the data's places
/// rather than a reference image: fonts and anti-aliasing differ between Chromium versions and
/// machines, the places of the samples do not, and a series drawn out of place fails here
/// where a tolerance on a whole image might let it through.)
#[test]
fn the_signal_plot_is_drawn_in_a_headless_chromium() {
    let Some(browser) = browser() else {
        assert!(
            std::env::var_os("PROTOCOL_REQUIRE_BROWSER").is_none(),
            "PROTOCOL_REQUIRE_BROWSER is set and no chromium is on the PATH"
        );
        eprintln!("no chromium on the PATH: the signal plot is not checked in a browser");
        return;
    };
    let (page, html) = report_with("signals", &["--plot", PLOTTED]);
    let dir = page.parent().expect("dir").to_path_buf();
    let window = [
        "--window-size=1280,1400",
        "--force-device-scale-factor=1",
        "--hide-scrollbars",
    ];
    let mut args = vec!["--dump-dom", "--enable-logging=stderr"];
    args.extend(window);
    let dom = headless(&browser, &page, &dir.join("profile-dom"), &args);
    assert!(dom.status.success(), "{}", text(&dom.stderr));
    let console: Vec<String> = text(&dom.stderr)
        .lines()
        .filter(|l| l.contains(":CONSOLE"))
        .map(str::to_string)
        .collect();
    assert!(console.is_empty(), "console messages: {console:#?}");
    let dom = text(&dom.stdout);
    let data = signal_data(&html);
    let series = data["series"].as_array().expect("series");
    let (_, root) = tag_attrs(&dom, "div id=\"signals\"", 0).expect("the plot");
    assert_eq!(
        root.get("data-errors").map(String::as_str),
        Some("0"),
        "{root:?}"
    );
    assert!(
        dom.contains("<ul id=\"plot-errors\"></ul>"),
        "no error listed"
    );
    let drawn = series.len().to_string();
    assert_eq!(root.get("data-drawn"), Some(&drawn), "every series drawn");

    let shot_path = dir.join("signals.png");
    let _ = std::fs::remove_file(&shot_path);
    let shot_arg = format!("--screenshot={}", shot_path.display());
    let mut args = vec![shot_arg.as_str()];
    args.extend(window);
    let out = headless(&browser, &page, &dir.join("profile-signals"), &args);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let shot = Shot::read(&shot_path);

    let mut from = 0;
    let mut checked_all = 0;
    for (panel, _) in data["panels"]
        .as_array()
        .expect("panels")
        .iter()
        .enumerate()
    {
        let (end, canvas) = tag_attrs(&dom, "canvas", from).expect("a canvas per panel");
        from = end;
        let num = |k: &str| -> f64 { canvas[k].parse().expect(k) };
        let (left, top, width, height) = (
            num("data-left"),
            num("data-top"),
            num("data-width"),
            num("data-height"),
        );
        let (x0, x1, y0, y1) = (
            num("data-x0"),
            num("data-x1"),
            num("data-y0"),
            num("data-y1"),
        );
        assert!(
            top + height < 1400.0,
            "panel {panel} lies in the window: {canvas:?}"
        );
        let place = |x: f64, y: f64| {
            (
                left + (x - x0) / (x1 - x0) * width,
                top + height - (y - y0) / (y1 - y0) * height,
            )
        };
        let mine: Vec<&serde_json::Value> = series.iter().filter(|s| s["panel"] == panel).collect();
        let lines: Vec<Vec<(f64, f64)>> = mine
            .iter()
            .map(|s| {
                let xs = s["x"].as_array().expect("x");
                let ys = s["y"].as_array().expect("y");
                xs.iter()
                    .zip(ys)
                    .map(|(x, y)| place(x.as_f64().expect("x"), y.as_f64().expect("y")))
                    .collect()
            })
            .collect();
        // The whole view spans the data, and each series' values lie in its range.
        for line in &lines {
            for p in line {
                assert!(p.0 >= left && p.0 <= left + width && p.1 >= top && p.1 <= top + height);
            }
        }
        for (k, s) in mine.iter().enumerate() {
            let colour = rgb(s["color"].as_str().expect("colour"));
            let covered = |p: (f64, f64)| {
                lines[k + 1..]
                    .iter()
                    .any(|l| l.windows(2).any(|w| to_segment(p, w[0], w[1]) < 4.0))
            };
            let checked: Vec<&(f64, f64)> = lines[k].iter().filter(|p| !covered(**p)).collect();
            let hits = checked
                .iter()
                .filter(|p| shot.near(p.0, p.1, 2, colour))
                .count();
            println!(
                "{}: {hits} of {} samples in its colour on the screenshot",
                s["name"],
                checked.len()
            );
            assert!(
                checked.len() >= 10,
                "{}: too few samples to check",
                s["name"]
            );
            assert!(
                hits * 100 >= checked.len() * 95,
                "{}: {hits} of {} samples show its colour",
                s["name"],
                checked.len()
            );
            checked_all += checked.len();
        }
        let mut background = 0;
        let mut all = 0;
        for y in (top as i64 + 2)..(top + height) as i64 - 2 {
            for x in (left as i64 + 2)..(left + width) as i64 - 2 {
                all += 1;
                background +=
                    usize::from(shot.pixel(x, y).is_some_and(|p| p.iter().all(|c| *c > 225)));
            }
        }
        assert!(
            background * 10 > all * 7,
            "panel {panel}: {background} of {all} pixels are background"
        );
    }
    assert!(checked_all > 100, "{checked_all} samples checked");

    // A plotter that throws: its error is in the DOM, and no series is counted as drawn.
    let broken = dir.join("broken.html");
    std::fs::write(&broken, html.replace("ctx.arc(", "ctx.arcc(")).expect("page");
    let mut args = vec!["--dump-dom"];
    args.extend(window);
    let dom = headless(&browser, &broken, &dir.join("profile-broken"), &args);
    let dom = text(&dom.stdout);
    let (_, root) = tag_attrs(&dom, "div id=\"signals\"", 0).expect("the plot");
    assert_ne!(
        root.get("data-errors").map(String::as_str),
        Some("0"),
        "{root:?}"
    );
    assert!(!root.contains_key("data-drawn"), "{root:?}");
    assert!(
        dom.contains("ctx.arcc is not a function"),
        "the error is listed"
    );
}
