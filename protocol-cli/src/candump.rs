//! Reading Linux SocketCAN logs: the `candump -L` log format (`(1700000000.123456) can0
//! 151#0001007B00000000`) and the default `candump` output (`  can0  151   [8]  00 01 00 7B 00
//! 00 00 00`, with or without a `-t` timestamp in front, with or without `-a` ASCII after), and
//! writing the log format back.
//!
//! This module owns the text formats only. Which frames a spec accepts is the interpreter's
//! business.
//!
//! ```
//! use protocol_cli::candump::parse_line;
//!
//! let log = parse_line("(1700000000.500000) can0 151#0001007B00000013").unwrap().unwrap();
//! let plain = parse_line("  can0  151   [8]  00 01 00 7B 00 00 00 13").unwrap().unwrap();
//! assert_eq!((log.id, log.data.as_slice()), (0x151, &[0, 1, 0, 0x7B, 0, 0, 0, 0x13][..]));
//! assert_eq!((plain.id, plain.data), (log.id, log.data));
//! assert_eq!(log.time.as_deref(), Some("1700000000.500000"));
//! ```

/// One CAN frame of a log.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct CanRecord {
    /// The timestamp as written (without its parentheses), if any.
    pub time: Option<String>,
    /// The interface (`can0`).
    pub interface: String,
    /// The identifier, without flags.
    pub id: u32,
    /// A 29-bit identifier (written with 8 hex digits).
    pub extended: bool,
    /// A remote request frame (no data).
    pub remote: bool,
    /// A CAN FD frame (`##` in the log format, a two-digit length in brackets otherwise).
    pub fd: bool,
    /// The data bytes.
    pub data: Vec<u8>,
}

/// The bits of a raw SocketCAN id that are flags, not the identifier (EFF, RTR, ERR).
const FLAG_BITS: u32 = 0xE000_0000;

fn hex_byte(text: &str) -> Option<u8> {
    if text.len() == 2 {
        u8::from_str_radix(text, 16).ok()
    } else {
        None
    }
}

fn parse_id(text: &str) -> Result<(u32, bool), String> {
    let raw = u32::from_str_radix(text, 16).map_err(|_| format!("invalid CAN id `{text}`"))?;
    let extended = text.len() > 3;
    let id = raw & !FLAG_BITS;
    let limit = if extended { 0x1FFF_FFFF } else { 0x7FF };
    if id > limit {
        return Err(format!("CAN id `{text}` is out of range"));
    }
    Ok((id, extended))
}

/// Splits a leading `(timestamp)` off a line.
fn split_time(line: &str) -> Result<(Option<String>, &str), String> {
    let line = line.trim();
    match line.strip_prefix('(') {
        Some(rest) => {
            let end = rest
                .find(')')
                .ok_or_else(|| "unclosed timestamp parenthesis".to_string())?;
            Ok((Some(rest[..end].trim().to_string()), rest[end + 1..].trim()))
        }
        None => Ok((None, line)),
    }
}

/// `ID#DATA`, `ID##FDATA` or `ID#R[len]`.
fn parse_log_frame(
    interface: &str,
    frame: &str,
    time: Option<String>,
) -> Result<CanRecord, String> {
    let (id_text, rest) = frame
        .split_once('#')
        .ok_or_else(|| format!("expected ID#DATA, got `{frame}`"))?;
    let (id, extended) = parse_id(id_text)?;
    let mut record = CanRecord {
        time,
        interface: interface.to_string(),
        id,
        extended,
        remote: false,
        fd: false,
        data: Vec::new(),
    };
    let data = if let Some(fd) = rest.strip_prefix('#') {
        record.fd = true;
        // One hex digit of FD flags precedes the data.
        fd.get(1..).unwrap_or("")
    } else if rest.starts_with(['R', 'r']) {
        record.remote = true;
        return Ok(record);
    } else {
        rest
    };
    let data: String = data.chars().filter(|c| *c != '.').collect();
    if data.len() % 2 != 0 {
        return Err(format!("odd number of hex digits in `{frame}`"));
    }
    record.data = (0..data.len())
        .step_by(2)
        .map(|i| hex_byte(&data[i..i + 2]).ok_or_else(|| format!("invalid data in `{frame}`")))
        .collect::<Result<_, _>>()?;
    Ok(record)
}

/// `iface ID [len] BYTES...` (the default output of `candump`).
fn parse_plain(rest: &str, time: Option<String>) -> Result<CanRecord, String> {
    let mut words = rest.split_whitespace();
    let interface = words.next().ok_or("missing interface")?;
    let id_text = words.next().ok_or("missing CAN id")?;
    let (id, extended) = parse_id(id_text)?;
    let len_text = words.next().ok_or("missing [length]")?;
    let len_digits = len_text
        .strip_prefix('[')
        .and_then(|l| l.strip_suffix(']'))
        .ok_or_else(|| format!("expected [length], got `{len_text}`"))?;
    let len: usize = len_digits
        .parse()
        .map_err(|_| format!("invalid length `{len_text}`"))?;
    let mut record = CanRecord {
        time,
        interface: interface.to_string(),
        id,
        extended,
        remote: false,
        fd: len_digits.len() == 2 || len > 8,
        data: Vec::new(),
    };
    let words: Vec<&str> = words.collect();
    if words.first() == Some(&"remote") {
        record.remote = true;
        return Ok(record);
    }
    // Data bytes, then maybe `'ascii'` (`candump -a`), which is not hex.
    for w in words.iter().take(len) {
        record
            .data
            .push(hex_byte(w).ok_or_else(|| format!("invalid data byte `{w}`"))?);
    }
    if record.data.len() != len {
        return Err(format!(
            "length says {len} bytes, the line has {}",
            record.data.len()
        ));
    }
    Ok(record)
}

/// Parses one line of either format. Blank lines and `#` comments give `Ok(None)`.
///
/// # Errors
/// A message saying what is wrong with the line.
pub fn parse_line(line: &str) -> Result<Option<CanRecord>, String> {
    let trimmed = line.trim();
    if trimmed.is_empty() || trimmed.starts_with('#') {
        return Ok(None);
    }
    let (time, rest) = split_time(trimmed)?;
    let words: Vec<&str> = rest.split_whitespace().collect();
    // The log format is `iface ID#DATA` (and sometimes a direction flag after it).
    if let [interface, frame, ..] = words.as_slice() {
        if frame.contains('#') {
            return parse_log_frame(interface, frame, time).map(Some);
        }
    }
    parse_plain(rest, time).map(Some)
}

/// A parsed log: the frames with their 1-based line numbers, and the lines that are not frames
/// with what is wrong with them.
pub type Log = (Vec<(usize, CanRecord)>, Vec<(usize, String)>);

/// Parses a whole log.
pub fn parse(text: &str) -> Log {
    let mut frames = Vec::new();
    let mut errors = Vec::new();
    for (i, line) in text.lines().enumerate() {
        match parse_line(line) {
            Ok(Some(r)) => frames.push((i + 1, r)),
            Ok(None) => {}
            Err(e) => errors.push((i + 1, e)),
        }
    }
    (frames, errors)
}

/// A frame in the `candump -L` log format: `(time) iface ID#DATA`.
pub fn format_log(time: &str, interface: &str, id: u32, extended: bool, data: &[u8]) -> String {
    let id = if extended {
        format!("{id:08X}")
    } else {
        format!("{id:03X}")
    };
    let data: String = data.iter().map(|b| format!("{b:02X}")).collect();
    format!("({time}) {interface} {id}#{data}")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn one(line: &str) -> CanRecord {
        parse_line(line).expect("parses").expect("a frame")
    }

    #[test]
    fn log_format_with_every_kind_of_frame() {
        let r = one("(1436509052.249713) vcan0 044#2A366C2BBA");
        assert_eq!(r.interface, "vcan0");
        assert_eq!((r.id, r.extended), (0x044, false));
        assert_eq!(r.data, [0x2A, 0x36, 0x6C, 0x2B, 0xBA]);
        let e = one("(0.1) can1 12345678#00");
        assert_eq!(
            (e.id, e.extended, e.data.as_slice()),
            (0x1234_5678, true, &[0][..])
        );
        let r = one("(0.2) can0 123#R");
        assert!(r.remote && r.data.is_empty());
        let fd = one("(0.3) can0 123##1112233");
        assert!(fd.fd);
        assert_eq!(fd.data, [0x11, 0x22, 0x33]);
        let empty = one("(0.4) can0 7FF#");
        assert!(empty.data.is_empty());
        let dotted = one("(0.5) can0 123#11.22.33");
        assert_eq!(dotted.data, [0x11, 0x22, 0x33]);
    }

    #[test]
    fn plain_format_with_and_without_timestamps_and_ascii() {
        let r = one("  can0  151   [8]  00 01 00 7B 00 00 00 13");
        assert_eq!((r.id, r.time.clone()), (0x151, None));
        assert_eq!(r.data.len(), 8);
        let t = one(" (2024-05-01 10:00:00.123456)  can0  131   [2]  FF 9C");
        assert_eq!(t.time.as_deref(), Some("2024-05-01 10:00:00.123456"));
        assert_eq!(t.data, [0xFF, 0x9C]);
        let a = one("  can0  200   [3]  41 42 43   'ABC'");
        assert_eq!(a.data, [0x41, 0x42, 0x43]);
        let x = one("  can0  1F334455   [1]  11");
        assert!(x.extended);
        let rtr = one("  can0  123   [0]  remote request");
        assert!(rtr.remote);
    }

    #[test]
    fn bad_lines_say_why_and_do_not_stop_the_log() {
        assert!(parse_line("can0 XYZ#00").is_err());
        assert!(parse_line("can0 123#0").is_err());
        assert!(parse_line("  can0  123   [4]  00 01").is_err());
        assert!(
            parse_line("  can0  800   [0]").is_err(),
            "11-bit id out of range"
        );
        let (frames, errors) =
            parse("# comment\n(0.0) can0 123#00\ngarbage\n\n(0.1) can0 124#01\n");
        assert_eq!(frames.len(), 2);
        assert_eq!(frames[1].0, 5);
        assert_eq!(errors.len(), 1);
        assert_eq!(errors[0].0, 3);
    }

    #[test]
    fn log_lines_read_back() {
        let line = format_log("0.000000", "can0", 0x151, false, &[1, 2, 0xAB]);
        assert_eq!(line, "(0.000000) can0 151#0102AB");
        let r = one(&line);
        assert_eq!((r.id, r.data), (0x151, vec![1, 2, 0xAB]));
    }
}
