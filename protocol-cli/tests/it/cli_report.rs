//! `protocol report`: the page is self-contained and holds every item of the capture, and it
//! renders in a real headless Chromium (the DOM after its script ran, and a screenshot).
//!
//! The browser test needs `chromium` (or the browser named by `PROTOCOL_CHROMIUM`). Without
//! one it says so and checks nothing more, unless `PROTOCOL_REQUIRE_BROWSER` is set, as CI
//! sets it: then a missing browser fails the test.

use crate::support;

use std::path::{Path, PathBuf};
use std::process::Command;

use support::{json_lines, protocol, text};

/// A report of the HFLink capture, written under the test's temporary directory.
fn report(name: &str) -> (PathBuf, String) {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    std::fs::create_dir_all(&dir).expect("temp dir");
    let path = dir.join("report.html");
    let out = protocol(
        &[
            "report",
            "specs/hflink.toml",
            "examples/captures/hflink.bin",
            "-o",
            path.to_str().expect("path"),
        ],
        b"",
    );
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
