//! `protocol twin SPEC (--pty | --serial PORT) [--values FILE] [--drop P] [--seed N]`: a device
//! that answers on a pseudo-terminal or a serial port as the spec's `[session]` says, so that a
//! host can be tested with no robot. The device is [`protocol_cli::twin`]; this module opens
//! the port, prints a pty's path and the summary, and stops on SIGINT.

use std::io::{self, Write};
use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::Arc;
use std::sync::atomic::AtomicBool;
use std::time::Duration;

use miette::{IntoDiagnostic, Result, WrapErr, miette};
use protocol_cli::twin::{Options, Tally, read_values, serve};
use protocol_dynamic::Interpreter;
use protocol_spec::ir::Transport;

use super::load_checked;

/// Arguments of `protocol twin`.
#[derive(Debug, clap::Args)]
#[command(group(clap::ArgGroup::new("port").required(true).args(["pty", "serial"])))]
pub struct Args {
    /// The spec file (it needs a `[session]`).
    spec: PathBuf,
    /// Open a pseudo-terminal and answer on it; its path (the port a host opens) is printed
    /// on the first line of stdout.
    #[arg(long)]
    pty: bool,
    /// Answer on this serial port.
    #[arg(long, value_name = "PORT")]
    serial: Option<String>,
    /// Baud rate of the serial port.
    #[arg(long, default_value_t = 115_200)]
    baud: u32,
    /// Payload values of the answers, per command name (`{"READ_ROBOT_SPEED": {"x": 1.5}}`):
    /// JSON, or TOML for a `.toml` file. A field left out, and every command left out, is the
    /// payload's all-zero value.
    #[arg(long, value_name = "FILE")]
    values: Option<PathBuf>,
    /// Drop each frame read and each answer with this probability (0 to 1), to see a host's
    /// retries.
    #[arg(long, value_name = "P", default_value_t = 0.0)]
    drop: f64,
    /// Seed of the drops: the same seed drops the same frames of the same exchanges.
    #[arg(long, value_name = "N", default_value_t = 1)]
    seed: u64,
}

/// Runs the twin until SIGINT or the port hangs up.
pub fn run(args: &Args) -> Result<ExitCode> {
    let protocol = match load_checked(&args.spec)? {
        Ok(p) => p,
        Err(code) => return Ok(code),
    };
    let Some(session) = &protocol.session else {
        return Err(miette!(
            "spec `{}` has no [session]: the twin answers as a session says",
            protocol.name
        ));
    };
    let format = &protocol.frames[session.frame];
    if matches!(format.transport, Transport::Can { .. }) {
        return Err(miette!(
            "spec `{}` holds its session on CAN frames (`{}`): the twin answers on a byte stream",
            protocol.name,
            format.name
        ));
    }
    if !(0.0..=1.0).contains(&args.drop) {
        return Err(miette!("`--drop {}`: a probability is 0 to 1", args.drop));
    }
    let values = match &args.values {
        Some(path) => read_values(path).map_err(|e| miette!("--values: {e}"))?,
        None => Default::default(),
    };
    let options = Options {
        values,
        drop: args.drop,
        seed: args.seed,
    };
    let interp = Interpreter::new(protocol);
    let codec = interp.codec();
    let stop = Arc::new(AtomicBool::new(false));
    signal_hook::flag::register(signal_hook::consts::SIGINT, Arc::clone(&stop))
        .into_diagnostic()?;
    let mut log = io::stderr().lock();
    let tally = match &args.serial {
        Some(path) => {
            let mut port = serialport::new(path, args.baud)
                .timeout(TICK)
                .open()
                .into_diagnostic()
                .wrap_err_with(|| format!("cannot open serial port `{path}`"))?;
            serve(&codec, &mut port, &options, &mut log, &stop).into_diagnostic()?
        }
        None => on_pty(|port| serve(&codec, port, &options, &mut log, &stop))?,
    };
    summary(&tally);
    Ok(ExitCode::SUCCESS)
}

/// How long a read waits before the twin looks at its clock (the watchdog, SIGINT).
const TICK: Duration = Duration::from_millis(20);

/// Opens a pseudo-terminal, prints the path of its port, and runs `f` on its other end. The
/// twin holds the port open too, so that a host may close and open it again.
#[cfg(unix)]
fn on_pty(f: impl FnOnce(&mut serialport::TTYPort) -> io::Result<Tally>) -> Result<Tally> {
    use serialport::SerialPort;
    let (mut device, host) = serialport::TTYPort::pair()
        .into_diagnostic()
        .wrap_err("cannot open a pseudo-terminal")?;
    device.set_timeout(TICK).into_diagnostic()?;
    let path = host
        .name()
        .ok_or_else(|| miette!("the pseudo-terminal has no path"))?;
    let mut out = io::stdout().lock();
    writeln!(out, "{path}").into_diagnostic()?;
    out.flush().into_diagnostic()?;
    let tally = f(&mut device).into_diagnostic()?;
    drop(host);
    Ok(tally)
}

#[cfg(not(unix))]
fn on_pty(_: impl FnOnce(&mut serialport::TTYPort) -> io::Result<Tally>) -> Result<Tally> {
    Err(miette!(
        "`--pty` needs a Unix pseudo-terminal; use `--serial PORT`"
    ))
}

fn summary(t: &Tally) {
    eprintln!(
        "twin: {} delivered, {} answered, {} duplicates, {} refused before the handshake, {} error replies, {} dropped, {} not answered, {} periodic",
        t.delivered,
        t.answered,
        t.duplicates,
        t.refused,
        t.error_replies,
        t.dropped,
        t.failed,
        t.periodic
    );
}
