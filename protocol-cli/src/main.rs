//! The `protocol` command: check, document, decode, encode, expand and diff protocol specs,
//! without compiling anything. Every command reads a spec through the same pipeline as the
//! `protocol!` macro; `decode` and `encode` run the run-time codec of `protocol-dynamic` on the
//! runtime's own engine.
//!
//! This file owns the command line (clap) and the exit status; each command lives in
//! [`cmd`].
#![forbid(unsafe_code)]

mod cmd;

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand, ValueEnum};

/// Describe a robot link once in a TOML spec; check, document, decode and encode it here.
#[derive(Debug, Parser)]
#[command(name = "protocol", version, about, max_term_width = 100)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Validate specs: every error with file:line:col, the spec line and a help; exit 1 on error.
    Check {
        /// The spec files.
        #[arg(required = true)]
        specs: Vec<PathBuf>,
        /// Print the diagnostics as a JSON array (for editors and CI) instead of text.
        #[arg(long)]
        json: bool,
    },
    /// Render the Markdown reference of a spec.
    Doc {
        /// The spec file.
        spec: PathBuf,
        /// Write to this file instead of stdout.
        #[arg(short, long)]
        output: Option<PathBuf>,
    },
    /// Decode a byte stream (file, stdin, hex, serial port) or a CAN log into frames and events.
    Decode(cmd::decode::Args),
    /// Encode frame objects (JSON Lines, as `decode --format json` prints them) into frames.
    Encode(cmd::encode::Args),
    /// Be the device: answer requests on a pseudo-terminal or a serial port as the spec's
    /// `[session]` says (answers, acknowledgements, NACKs before the handshake, duplicates
    /// answered again), with payload values from a file or zeros, and optional dropped frames.
    Twin(cmd::twin::Args),
    /// Write one self-contained HTML page about a capture: link statistics, frames per
    /// command, signals plotted over the capture, link quality over the capture, and a hex
    /// view with every field outlined.
    Report {
        /// The spec file.
        spec: PathBuf,
        /// The capture (raw bytes).
        capture: PathBuf,
        /// Write to this file (default: the capture's path with `.html`).
        #[arg(short, long)]
        output: Option<PathBuf>,
        /// The frame format to decode (default: the first).
        #[arg(long)]
        frame: Option<String>,
        /// The direction of the frames, for a spec whose directions no header field tells
        /// (`given = true`): a direction named in the spec (`request`, `response`).
        #[arg(long, value_name = "NAME")]
        direction: Option<String>,
        /// Fields to plot over the capture, comma-separated: `COMMAND.payload.FIELD`,
        /// `COMMAND.header.FIELD`, or `payload.FIELD` for every command that has it (an
        /// array's element `payload.v[2]`, or all of them `payload.v`). Default: the fields
        /// with a scale or a unit of the most frequent commands.
        #[arg(long, value_name = "NAMES")]
        plot: Vec<String>,
    },
    /// Print the Rust code the `protocol!` macro generates for a spec, formatted (in a build
    /// with the `expand` feature: `cargo install protocol-cli --features expand`).
    Expand {
        /// The spec file.
        spec: PathBuf,
    },
    /// Generate a peer codec in another language from a spec.
    #[command(subcommand)]
    Gen(Gen),
    /// Write a spec from a definition in another language.
    #[command(subcommand)]
    Import(Import),
    /// Write a capture for other tools (pcap for Wireshark, CSV tables, MCAP for Foxglove).
    #[command(subcommand)]
    Export(Export),
    /// Report every change between two versions of a spec, once, as breaking the wire, breaking
    /// the generated Rust source (a rename; an added command or enum value, which an exhaustive
    /// `match` must name), or compatible.
    #[command(after_help = "Exit status:\n  \
        0  compatible at both levels: the wire and the generated Rust source\n  \
        1  anything breaks, the wire or the source (source-breaking changes included)\n  \
        2  a spec cannot be read or is invalid (its errors are printed)")]
    Diff {
        /// The old version.
        old: PathBuf,
        /// The new version.
        new: PathBuf,
        /// Print the changes as JSON.
        #[arg(long)]
        json: bool,
    },
}

/// The languages of `gen`.
#[derive(Debug, Subcommand)]
enum Gen {
    /// A C99 header and source file (`NAME.h`, `NAME.c`): structs, encoders, a frame decoder
    /// and a stream decoder, no heap, no dependency beyond the C standard headers.
    C {
        /// The spec file.
        spec: PathBuf,
        /// The directory to write the two files into (created if missing).
        #[arg(short, long)]
        output: PathBuf,
    },
    /// A Wireshark Lua dissector (`NAME.lua`): every field filterable, checks verified, frames
    /// found in raw serial captures (DLT_USER0), UDP and TCP ports, and SocketCAN captures.
    Wireshark {
        /// The spec file.
        spec: PathBuf,
        /// The directory to write the file into (created if missing).
        #[arg(short, long)]
        output: PathBuf,
    },
}

/// The formats of `export`.
#[derive(Debug, Subcommand)]
enum Export {
    /// Raw serial bytes (or a candump log) as a pcap file the dissector of `gen wireshark` reads.
    Pcap(cmd::export::PcapArgs),
    /// The decoded frames as one CSV file per command (columns `header.x`, `payload.y`).
    Csv(cmd::export_data::Args),
    /// The decoded frames as an MCAP file: a channel per command, JSON messages with a
    /// schema, log times from the capture (Foxglove opens it).
    Mcap(cmd::export_data::Args),
}

/// The languages of `import`.
#[derive(Debug, Subcommand)]
enum Import {
    /// A MAVLink dialect's XML (and the files it includes) as a spec: a command and a struct
    /// per message, fields in wire order, each CRC_EXTRA derived from the definition.
    Mavlink {
        /// The dialect's XML file (`common.xml`).
        dialect: PathBuf,
        /// Write to this file instead of stdout.
        #[arg(short, long)]
        output: Option<PathBuf>,
    },
}

/// How `decode` prints.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum Format {
    /// One aligned line per frame (the default on a terminal).
    Table,
    /// JSON Lines: one object per frame or event (the default otherwise).
    Json,
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Check { specs, json } => cmd::check::run(&specs, json),
        Command::Doc { spec, output } => cmd::doc::run(&spec, output.as_deref()),
        Command::Decode(args) => cmd::decode::run(&args),
        Command::Encode(args) => cmd::encode::run(&args),
        Command::Twin(args) => cmd::twin::run(&args),
        Command::Expand { spec } => cmd::expand::run(&spec),
        Command::Report {
            spec,
            capture,
            output,
            frame,
            direction,
            plot,
        } => cmd::report::run(&cmd::report::Args {
            spec: &spec,
            capture: &capture,
            output: output.as_deref(),
            frame: frame.as_deref(),
            direction: direction.as_deref(),
            plot: &plot,
        }),
        Command::Gen(Gen::C { spec, output }) => cmd::generate::c(&spec, &output),
        Command::Gen(Gen::Wireshark { spec, output }) => cmd::wireshark::run(&spec, &output),
        Command::Import(Import::Mavlink { dialect, output }) => {
            cmd::import::mavlink(&dialect, output.as_deref())
        }
        Command::Export(Export::Pcap(args)) => cmd::export::pcap_run(&args),
        Command::Export(Export::Csv(args)) => cmd::export_data::csv_run(&args),
        Command::Export(Export::Mcap(args)) => cmd::export_data::mcap_run(&args),
        Command::Diff { old, new, json } => cmd::diff::run(&old, &new, json),
    };
    match result {
        Ok(code) => code,
        Err(e) => {
            cmd::print_error(&e);
            ExitCode::FAILURE
        }
    }
}
