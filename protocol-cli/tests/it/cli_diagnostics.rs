//! One diagnostics path: a spec's errors read the same, byte for byte, in the `protocol!`
//! macro's compile error and on the stderr of every command that loads a spec; a file that
//! cannot be read is worded the same by every command; colour only on a terminal, never with
//! `NO_COLOR`.

use crate::support;

use std::process::{Command, Output, Stdio};

use support::{root, text};

/// Bad specs of the diagnostics catalogue and of these tests, relative to the workspace root.
const BAD_SPECS: &[&str] = &[
    "protocol-cli/tests/fixtures/bad.toml",
    "protocol-codegen/tests/invalid/crc_given_a_catalogue_name.toml",
    "protocol-codegen/tests/invalid/sync_array_of_arrays.toml",
    "protocol-codegen/tests/invalid/integer_beyond_64_bits.toml",
    "protocol-codegen/tests/invalid/type_width_not_on_the_wire.toml",
    "protocol-codegen/tests/invalid/every_table_reports_at_once.toml",
    "protocol-codegen/tests/invalid/invalid_toml.toml",
];

/// Runs the binary in `dir` with `NO_COLOR` set or not; stdin is empty, stdout and stderr are
/// pipes.
fn run_in(dir: &std::path::Path, args: &[&str], no_color: bool) -> Output {
    let mut command = Command::new(env!("CARGO_BIN_EXE_protocol"));
    command
        .args(args)
        .current_dir(dir)
        .env_remove("NO_COLOR")
        .stdin(Stdio::null());
    if no_color {
        command.env("NO_COLOR", "1");
    }
    command.output().expect("the binary runs")
}

/// The message of the `protocol!` macro's compile error for `path` (relative to this crate's
/// manifest directory, as the macro reads it).
fn macro_message(path: &str) -> String {
    let tokens = protocol_codegen::input::protocol_macro(quote::quote!(#path));
    let mac: syn::Macro = syn::parse2(tokens.clone()).unwrap_or_else(|e| panic!("{e}: {tokens}"));
    assert!(
        mac.path.is_ident("compile_error")
            || mac
                .path
                .segments
                .last()
                .is_some_and(|s| s.ident == "compile_error")
    );
    mac.parse_body::<syn::LitStr>().expect("a string").value()
}

#[test]
fn the_macro_and_every_command_render_a_spec_error_alike() {
    // The macro reads paths relative to the calling crate, this one: run the commands there
    // too, so that both name the spec by the same path.
    let here = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let capture = "tests/fixtures/bad.toml";
    for spec in BAD_SPECS {
        let path = format!("../{spec}");
        let expected = macro_message(&path);
        assert!(
            expected.contains(&format!("in spec {path}\n\n")),
            "{expected}"
        );
        for args in [
            vec!["check", path.as_str()],
            vec!["doc", path.as_str()],
            vec!["expand", path.as_str()],
            vec!["decode", path.as_str(), "-"],
            vec!["encode", path.as_str()],
            vec!["report", path.as_str(), capture, "-o", "/dev/null"],
            vec!["diff", "../specs/hflink.toml", path.as_str()],
        ] {
            let out = run_in(here, &args, false);
            assert!(!out.status.success(), "{args:?}");
            assert_eq!(text(&out.stderr), expected, "{args:?}");
            assert!(out.stdout.is_empty(), "{args:?}");
        }
    }
}

#[test]
fn cannot_read_is_worded_alike_by_every_command() {
    let missing = "specs/no-such-file.toml";
    let cases: [(&str, Vec<&str>); 10] = [
        ("spec", vec!["check", missing]),
        ("spec", vec!["doc", missing]),
        ("spec", vec!["expand", missing]),
        ("spec", vec!["decode", missing, "-"]),
        ("spec", vec!["encode", missing]),
        ("spec", vec!["diff", "specs/hflink.toml", missing]),
        ("capture", vec!["report", "specs/hflink.toml", missing]),
        ("input", vec!["decode", "specs/hflink.toml", missing]),
        ("input", vec!["encode", "specs/hflink.toml", missing]),
        (
            "candump log",
            vec!["decode", "specs/scout.toml", "--candump", missing],
        ),
    ];
    for (what, args) in cases {
        let out = run_in(&root(), &args, true);
        assert!(!out.status.success(), "{args:?}");
        let stderr = text(&out.stderr);
        let first = stderr.lines().next().unwrap_or("");
        assert!(
            first.starts_with(&format!("error: cannot read {what} `{missing}`: ")),
            "{args:?}: {stderr}"
        );
        assert_eq!(stderr.lines().count(), 1, "{args:?}: {stderr}");
    }
    // The macro says the same sentence (rustc writes its `error: `), with where it looked.
    let here = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let relative = format!("../{missing}");
    let from_macro = macro_message(&relative);
    let cli = text(&run_in(here, &["check", &relative], true).stderr);
    assert_eq!(
        from_macro.lines().next().map(|l| format!("error: {l}")),
        cli.lines().next().map(str::to_string)
    );
}

/// The command's stderr when it is a terminal (the slave of a pseudo-terminal pair).
#[cfg(unix)]
fn stderr_on_a_terminal(args: &[&str], no_color: bool) -> String {
    use std::io::Read;

    use rustix::fs::{Mode, OFlags};
    use rustix::pty::{OpenptFlags, grantpt, openpt, ptsname, unlockpt};
    let master =
        openpt(OpenptFlags::RDWR | OpenptFlags::NOCTTY | OpenptFlags::CLOEXEC).expect("openpt");
    grantpt(&master).expect("grantpt");
    unlockpt(&master).expect("unlockpt");
    let name = ptsname(&master, Vec::new()).expect("ptsname");
    let slave = rustix::fs::open(
        name.as_c_str(),
        OFlags::RDWR | OFlags::NOCTTY,
        Mode::empty(),
    )
    .expect("open the slave");
    let mut command = Command::new(env!("CARGO_BIN_EXE_protocol"));
    command
        .args(args)
        .current_dir(root())
        .env_remove("NO_COLOR")
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::from(std::fs::File::from(slave)));
    if no_color {
        command.env("NO_COLOR", "1");
    }
    let status = command.status().expect("the binary runs");
    assert!(!status.success());
    // Drop every handle of the slave (the command's ended with it): reading the master then
    // ends with an error once what was written is read.
    drop(command);
    let mut master = std::fs::File::from(master);
    let mut out = Vec::new();
    let mut buf = [0u8; 4096];
    while let Ok(n) = master.read(&mut buf) {
        if n == 0 {
            break;
        }
        out.extend_from_slice(&buf[..n]);
    }
    text(&out)
}

#[cfg(unix)]
#[test]
fn colour_on_a_terminal_only_and_never_with_no_color() {
    let args = ["check", "protocol-cli/tests/fixtures/bad.toml"];
    let coloured = stderr_on_a_terminal(&args, false);
    assert!(coloured.contains("\x1b[1;31merror\x1b[0m"), "{coloured:?}");
    let plain = stderr_on_a_terminal(&args, true);
    assert!(plain.contains("error: unknown struct `Moov`"), "{plain:?}");
    assert!(!plain.contains('\x1b'), "{plain:?}");
    // Through a pipe: plain, `NO_COLOR` or not.
    let piped = run_in(&root(), &args, false);
    assert!(!text(&piped.stderr).contains('\x1b'));
    assert!(text(&piped.stderr).contains("error: unknown struct `Moov`"));
}
