//! MCAP export: one channel per command (topic `/COMMAND`), each with the JSON Schema of its
//! frames ([`super::schema`]), messages encoded as JSON: the objects `protocol decode --format
//! json` prints. Foxglove and the `mcap` tools read it as it is.
//!
//! A message's log time is the frame's receive time when the capture has one (a candump
//! log's timestamps); otherwise the time its first byte took to arrive at the link's rate
//! (`offset * 10 / baud` seconds: 8N1 framing, ten bits a byte) for a byte stream, or one
//! millisecond a record for a CAN log without times. The publish time is the log time.

use std::collections::BTreeMap;
use std::io::{self, Seek, Write};

use protocol_spec::ir::Protocol;

use super::{Record, by_key, schema};

/// How log times are made for frames without a receive time.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Clock {
    /// A byte stream at this many bits per second (ten bits a byte).
    Baud(u32),
    /// Records one millisecond apart (a CAN log without times).
    Records,
}

impl Clock {
    /// The log time of a frame, in nanoseconds.
    pub fn log_time(self, r: &Record) -> u64 {
        r.time_ns.unwrap_or_else(|| match self {
            Clock::Baud(baud) => {
                let ns = u128::from(r.offset()) * 10 * 1_000_000_000 / u128::from(baud.max(1));
                u64::try_from(ns).unwrap_or(u64::MAX)
            }
            Clock::Records => r.offset().saturating_mul(1_000_000),
        })
    }
}

/// What an export wrote: per channel, its topic and message count.
pub type Written = Vec<(String, usize)>;

/// Writes the records to `out` as MCAP; returns the channels with their message counts.
///
/// # Errors
/// When `out` cannot be written, or the `mcap` writer refuses a record.
pub fn write<W: Write + Seek>(
    p: &Protocol,
    records: &[Record],
    clock: Clock,
    out: W,
) -> io::Result<Written> {
    let mut w = mcap::Writer::new(out).map_err(io::Error::other)?;
    // Every channel first, then the messages in the capture's order (the order of their
    // log times), each channel counting its own sequence.
    let mut channels: Vec<(&str, u16, usize)> = Vec::new();
    for (key, _) in by_key(records) {
        let command = p.commands.iter().position(|c| c.name == key);
        let format = p.frames.iter().position(|f| f.name == key).unwrap_or(0);
        let schema = schema::frame_schema(p, command, format);
        let schema_id = w
            .add_schema(
                &format!("{}.{key}", p.name),
                "jsonschema",
                schema.to_string().as_bytes(),
            )
            .map_err(io::Error::other)?;
        let metadata = BTreeMap::from([("spec".to_string(), p.name.clone())]);
        let channel_id = w
            .add_channel(schema_id, &format!("/{key}"), "json", &metadata)
            .map_err(io::Error::other)?;
        channels.push((key, channel_id, 0));
    }
    for r in records {
        let Some((_, channel_id, count)) = channels.iter_mut().find(|(k, ..)| *k == r.key()) else {
            continue;
        };
        let time = clock.log_time(r);
        let header = mcap::records::MessageHeader {
            channel_id: *channel_id,
            sequence: u32::try_from(*count).unwrap_or(u32::MAX),
            log_time: time,
            publish_time: time,
        };
        *count += 1;
        let data = serde_json::to_vec(&r.value).map_err(io::Error::other)?;
        w.write_to_known_channel(&header, &data)
            .map_err(io::Error::other)?;
    }
    let written = channels
        .into_iter()
        .map(|(key, _, n)| (format!("/{key}"), n))
        .collect();
    w.finish().map_err(io::Error::other)?;
    Ok(written)
}
