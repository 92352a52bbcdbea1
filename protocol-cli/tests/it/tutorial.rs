//! The `protocol` commands of `docs/tutorial.md` print what the tutorial shows: every line
//! `$ protocol ARGS` of a `console` block is run in the tutorial's crate (`examples/tutorial`,
//! whose capture is the one the tutorial's host writes), and its standard output must be the
//! lines that follow it.

use crate::support;

use std::process::Command;

use support::{root, text};

/// The (arguments, output) of every `$ protocol` line of the tutorial's console blocks.
fn commands() -> Vec<(String, String)> {
    let md = std::fs::read_to_string(root().join("docs/tutorial.md")).expect("the tutorial");
    let mut out: Vec<(String, String)> = Vec::new();
    let mut in_console = false;
    let mut current: Option<(String, String)> = None;
    for line in md.lines() {
        if let Some(info) = line.strip_prefix("```") {
            out.extend(current.take());
            in_console = !in_console && info.starts_with("console");
            continue;
        }
        if !in_console {
            continue;
        }
        if let Some(cmd) = line.strip_prefix("$ ") {
            out.extend(current.take());
            current = cmd
                .strip_prefix("protocol ")
                .map(|args| (args.to_string(), String::new()));
        } else if let Some((_, output)) = &mut current {
            output.push_str(line);
            output.push('\n');
        }
    }
    out
}

#[test]
fn the_tutorials_commands_print_what_it_shows() {
    let commands = commands();
    assert!(commands.len() >= 3, "check, decode and diff: {commands:?}");
    for (args, shown) in commands {
        let args: Vec<&str> = args.split_whitespace().collect();
        let out = Command::new(env!("CARGO_BIN_EXE_protocol"))
            .args(&args)
            .current_dir(root().join("examples/tutorial"))
            .env("NO_COLOR", "1")
            .output()
            .expect("the binary runs");
        assert_eq!(
            text(&out.stdout),
            shown,
            "`protocol {}` prints otherwise than docs/tutorial.md shows (stderr: {})",
            args.join(" "),
            text(&out.stderr)
        );
    }
}
