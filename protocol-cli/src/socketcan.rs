//! Live CAN input (`protocol decode SPEC --can IFACE`): frames read from a Linux SocketCAN
//! interface (`can0`, `vcan0`) become the same [`CanRecord`]s a candump log gives, so a live bus
//! and a replayed log are decoded by the one session code.
//!
//! This module owns opening the interface, reading until SIGINT, and the conversion of any
//! `embedded_can::Frame` (the `socketcan` crate's frames implement it) into a record.

use std::io;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, SystemTime, UNIX_EPOCH};

use protocol_runtime::embedded_can::{Frame, Id};

use crate::candump::CanRecord;

/// The record of a frame received on `interface`, stamped with `time` (seconds since the
/// epoch, as candump writes it). A remote frame keeps its id and no data.
pub fn record<F: Frame>(frame: &F, interface: &str, time: Option<String>) -> CanRecord {
    let (id, extended) = match frame.id() {
        Id::Standard(id) => (u32::from(id.as_raw()), false),
        Id::Extended(id) => (id.as_raw(), true),
    };
    let remote = frame.is_remote_frame();
    CanRecord {
        time,
        interface: interface.to_string(),
        id,
        extended,
        remote,
        fd: false,
        data: if remote {
            Vec::new()
        } else {
            frame.data().to_vec()
        },
    }
}

/// The time now as candump writes it (`1700000000.500000`).
fn now() -> Option<String> {
    let t = SystemTime::now().duration_since(UNIX_EPOCH).ok()?;
    Some(format!("{}.{:06}", t.as_secs(), t.subsec_micros()))
}

/// A SocketCAN interface read until SIGINT (or until the interface goes away).
pub struct Live {
    socket: socketcan::CanSocket,
    interface: String,
    interrupted: Arc<AtomicBool>,
}

impl Live {
    /// Opens `interface` for reading raw CAN frames; SIGINT ends [`next`](Self::next).
    ///
    /// # Errors
    /// When the interface does not exist or cannot be opened, or the handler cannot be set.
    pub fn open(interface: &str) -> io::Result<Self> {
        use socketcan::Socket as _;
        let socket = socketcan::CanSocket::open(interface)?;
        // Wake up regularly to notice SIGINT.
        socket.set_read_timeout(Duration::from_millis(100))?;
        let interrupted = Arc::new(AtomicBool::new(false));
        signal_hook::flag::register(signal_hook::consts::SIGINT, Arc::clone(&interrupted))?;
        Ok(Live {
            socket,
            interface: interface.to_string(),
            interrupted,
        })
    }

    /// The next frame of the bus; `None` once interrupted or when the interface is gone. Error
    /// frames (bus errors the controller reports) are counted in `errors` and skipped.
    ///
    /// # Errors
    /// A read error other than a timeout.
    pub fn next(&mut self, errors: &mut u64) -> io::Result<Option<CanRecord>> {
        use socketcan::Socket as _;
        loop {
            if self.interrupted.load(Ordering::Relaxed) {
                return Ok(None);
            }
            match self.socket.read_frame() {
                Ok(socketcan::CanFrame::Error(_)) => *errors += 1,
                Ok(frame) => return Ok(Some(record(&frame, &self.interface, now()))),
                Err(e)
                    if matches!(
                        e.kind(),
                        io::ErrorKind::WouldBlock
                            | io::ErrorKind::TimedOut
                            | io::ErrorKind::Interrupted
                    ) => {}
                // ENODEV / ENETDOWN: the interface was removed or brought down.
                Err(e) if matches!(e.raw_os_error(), Some(19) | Some(100)) => return Ok(None),
                Err(e) => return Err(e),
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::candump;
    use protocol_runtime::CanFrame;
    use protocol_runtime::embedded_can::{ExtendedId, StandardId};

    /// A frame read through the `embedded_can::Frame` trait is the record the same frame has
    /// in a candump log, standard and extended.
    #[test]
    fn live_frames_are_log_records() {
        let log = "(1.000000) vcan0 151#0102030405060708\n(2.000000) vcan0 18FF50E5#AA55\n";
        let (records, errors) = candump::parse(log);
        assert!(errors.is_empty());
        let frames = [
            <CanFrame as Frame>::new(
                StandardId::new(0x151).expect("11 bits"),
                &[1, 2, 3, 4, 5, 6, 7, 8],
            ),
            <CanFrame as Frame>::new(
                ExtendedId::new(0x18FF_50E5).expect("29 bits"),
                &[0xAA, 0x55],
            ),
        ];
        for ((_, logged), (frame, time)) in records
            .iter()
            .zip(frames.iter().zip(["1.000000", "2.000000"]))
        {
            let frame = frame.as_ref().expect("a data frame");
            assert_eq!(&record(frame, "vcan0", Some(time.into())), logged);
        }
    }

    #[test]
    fn a_missing_interface_is_an_error() {
        let err = Live::open("nosuchcan0").err().expect("no such interface");
        // ENODEV: no interface of that name.
        assert_eq!(err.raw_os_error(), Some(19), "{err}");
    }
}
