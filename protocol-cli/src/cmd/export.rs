//! `protocol export`: a capture written for other tools. `pcap` writes raw serial bytes as
//! packets of a user link type (DLT_USER0, 147, by default), or a candump log as SocketCAN
//! packets (link type 227), which the dissector of `protocol gen wireshark` reads.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use miette::{IntoDiagnostic, Result, WrapErr, miette};
use protocol_cli::candump;

/// The link type of raw serial bytes: DLT_USER0.
pub const DLT_USER0: u32 = 147;
/// The link type of SocketCAN frames.
pub const DLT_CAN_SOCKETCAN: u32 = 227;

/// The arguments of `export pcap`.
#[derive(Debug, clap::Args)]
pub struct PcapArgs {
    /// The input: a binary file of raw serial bytes, or `-` for stdin.
    #[arg(default_value = "-")]
    pub input: PathBuf,
    /// The input is hex text (whitespace, `0x`, `,` and `:` are ignored).
    #[arg(long)]
    pub hex: bool,
    /// Read a `candump` log instead, written as SocketCAN packets.
    #[arg(long, value_name = "FILE", conflicts_with = "hex")]
    pub candump: Option<PathBuf>,
    /// The most bytes per packet (a serial read's chunk; frames may be cut across packets).
    #[arg(long, default_value_t = 64, value_parser = clap::value_parser!(u32).range(1..=65535))]
    pub chunk: u32,
    /// The user link type: n of DLT_USERn (0 to 15).
    #[arg(long, default_value_t = 0, value_parser = clap::value_parser!(u32).range(0..=15))]
    pub user: u32,
    /// The pcap file to write.
    #[arg(short, long)]
    pub output: PathBuf,
}

/// A classic pcap file: the global header, then each record with its time.
fn pcap(link_type: u32, packets: &[(u64, Vec<u8>)]) -> Vec<u8> {
    let mut out = Vec::new();
    out.extend_from_slice(&0xA1B2_C3D4u32.to_le_bytes());
    out.extend_from_slice(&2u16.to_le_bytes());
    out.extend_from_slice(&4u16.to_le_bytes());
    out.extend_from_slice(&0i32.to_le_bytes());
    out.extend_from_slice(&0u32.to_le_bytes());
    out.extend_from_slice(&65535u32.to_le_bytes());
    out.extend_from_slice(&link_type.to_le_bytes());
    for (micros, data) in packets {
        let len = data.len() as u32;
        out.extend_from_slice(&((micros / 1_000_000) as u32).to_le_bytes());
        out.extend_from_slice(&((micros % 1_000_000) as u32).to_le_bytes());
        out.extend_from_slice(&len.to_le_bytes());
        out.extend_from_slice(&len.to_le_bytes());
        out.extend_from_slice(data);
    }
    out
}

/// A SocketCAN packet: the id with its flags (big-endian), the length, padding, the data.
fn socketcan(r: &candump::CanRecord) -> Vec<u8> {
    let mut id = r.id;
    if r.extended {
        id |= 0x8000_0000;
    }
    if r.remote {
        id |= 0x4000_0000;
    }
    let mut out = id.to_be_bytes().to_vec();
    out.extend_from_slice(&[r.data.len() as u8, 0, 0, 0]);
    out.extend_from_slice(&r.data);
    out
}

/// Microseconds of a candump time (`1700000000.500000`), 0 without one.
fn candump_micros(time: Option<&str>) -> u64 {
    let Some((secs, frac)) = time.and_then(|t| t.split_once('.')) else {
        return 0;
    };
    let frac: String = frac.chars().chain(std::iter::repeat('0')).take(6).collect();
    secs.parse::<u64>().unwrap_or(0) * 1_000_000 + frac.parse::<u64>().unwrap_or(0)
}

fn read_input(path: &Path) -> Result<Vec<u8>> {
    if path == Path::new("-") {
        let mut buf = Vec::new();
        std::io::Read::read_to_end(&mut std::io::stdin(), &mut buf).into_diagnostic()?;
        return Ok(buf);
    }
    std::fs::read(path)
        .into_diagnostic()
        .wrap_err_with(|| format!("cannot read input `{}`", path.display()))
}

/// `export pcap`: raw bytes in packets of `--chunk` bytes, one millisecond apart (a raw byte
/// file has no times), or a candump log's frames at their logged times.
pub fn pcap_run(args: &PcapArgs) -> Result<ExitCode> {
    let (link, packets) = match &args.candump {
        Some(log) => {
            let text = std::fs::read_to_string(log)
                .into_diagnostic()
                .wrap_err_with(|| format!("cannot read `{}`", log.display()))?;
            let (frames, errors) = candump::parse(&text);
            if let Some((line, e)) = errors.first() {
                return Err(miette!("{}:{line}: {e}", log.display()));
            }
            let packets = frames
                .iter()
                .map(|(_, r)| (candump_micros(r.time.as_deref()), socketcan(r)))
                .collect::<Vec<_>>();
            (DLT_CAN_SOCKETCAN, packets)
        }
        None => {
            let raw = read_input(&args.input)?;
            let bytes = if args.hex {
                let text = String::from_utf8_lossy(&raw);
                protocol_dynamic::parse_hex(&text).ok_or_else(|| miette!("the input is not hex"))?
            } else {
                raw
            };
            let packets = bytes
                .chunks(args.chunk as usize)
                .enumerate()
                .map(|(i, c)| (i as u64 * 1000, c.to_vec()))
                .collect::<Vec<_>>();
            (DLT_USER0 + args.user, packets)
        }
    };
    std::fs::write(&args.output, pcap(link, &packets))
        .into_diagnostic()
        .wrap_err_with(|| format!("cannot write `{}`", args.output.display()))?;
    eprintln!("{} packets, link type {link}", packets.len());
    Ok(ExitCode::SUCCESS)
}
