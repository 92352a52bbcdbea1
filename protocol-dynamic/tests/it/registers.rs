//! The register maps of the Dynamixel specs (`[registers]`): on the same bytes, the generated
//! code's register accessors (`registers::NAME.read(registers::read_answer(&read, &status))`,
//! `registers::write_data(&write)`) and the run-time codec's conversation
//! ([`Conversation`]'s `registers`) give the same registers with the same values, for READs
//! of every start address and length (whole registers, runs that start or end inside one,
//! answers shorter than asked) and for WRITEs; and the codec notes every run that is not whole
//! registers.

use std::sync::OnceLock;

use crate::support;

use protocol_dynamic::registers::RegisterValues;
use protocol_dynamic::{Conversation, Interpreter, Value};
use protocol_kit::Bytes;
use protocol_kit::registers::Window;
use support::interpreter;

protocol_kit::protocol!("../specs/dynamixel.toml");
protocol_kit::protocol!("../specs/dynamixel1.toml");

/// A generated register's value as the run-time codec holds it.
trait AsValue {
    fn into_value(self) -> Value;
}

macro_rules! as_value {
    ($variant:ident: $($t:ty),*) => {
        $(impl AsValue for $t {
            fn into_value(self) -> Value {
                Value::$variant(self.into())
            }
        })*
    };
}
as_value!(UInt: u8, u16, u32);
as_value!(Int: i16, i32);
as_value!(F32: f32);
as_value!(F64: f64);

/// Checks every register of `$module`'s map, listed here in full, against the codec's values
/// in `$window`; gives the bytes of the registers the window holds whole.
macro_rules! agree {
    ($module:ident, $window:expr, $codec:expr, [$($reg:ident),* $(,)?]) => {{
        use $module::registers;
        let (window, codec): (Window<'_>, &RegisterValues) = ($window, $codec);
        let mut names = Vec::new();
        let mut whole = 0;
        $(
            let r = registers::$reg;
            let generated = r.read(window).map(AsValue::into_value);
            assert_eq!(generated.as_ref(), codec.values.get(r.name()), "`{}` in {window:?}", r.name());
            if generated.is_some() {
                whole += r.size();
            }
            names.push(r.name());
        )*
        let map: Vec<&str> = registers::MAP.iter().map(|(n, _, _)| *n).collect();
        assert_eq!(names, map, "the test lists every register of the map");
        whole
    }};
}

/// [`agree!`] over every register of the XM430-W350's map (`dynamixel`), listed once.
macro_rules! agree_xm430 {
    ($window:expr, $codec:expr) => {
        agree!(
            dynamixel,
            $window,
            $codec,
            [
                MODEL_NUMBER,
                MODEL_INFORMATION,
                FIRMWARE_VERSION,
                ID,
                BAUD_RATE,
                RETURN_DELAY_TIME,
                DRIVE_MODE,
                OPERATING_MODE,
                SECONDARY_ID,
                PROTOCOL_TYPE,
                HOMING_OFFSET,
                MOVING_THRESHOLD,
                TEMPERATURE_LIMIT,
                MAX_VOLTAGE_LIMIT,
                MIN_VOLTAGE_LIMIT,
                PWM_LIMIT,
                CURRENT_LIMIT,
                VELOCITY_LIMIT,
                MAX_POSITION_LIMIT,
                MIN_POSITION_LIMIT,
                STARTUP_CONFIGURATION,
                SHUTDOWN,
                TORQUE_ENABLE,
                LED,
                STATUS_RETURN_LEVEL,
                REGISTERED_INSTRUCTION,
                HARDWARE_ERROR_STATUS,
                VELOCITY_I_GAIN,
                VELOCITY_P_GAIN,
                POSITION_D_GAIN,
                POSITION_I_GAIN,
                POSITION_P_GAIN,
                FEEDFORWARD_2ND_GAIN,
                FEEDFORWARD_1ST_GAIN,
                BUS_WATCHDOG,
                GOAL_PWM,
                GOAL_CURRENT,
                GOAL_VELOCITY,
                PROFILE_ACCELERATION,
                PROFILE_VELOCITY,
                GOAL_POSITION,
                REALTIME_TICK,
                MOVING,
                MOVING_STATUS,
                PRESENT_PWM,
                PRESENT_CURRENT,
                PRESENT_VELOCITY,
                PRESENT_POSITION,
                VELOCITY_TRAJECTORY,
                POSITION_TRAJECTORY,
                PRESENT_INPUT_VOLTAGE,
                PRESENT_TEMPERATURE,
                BACKUP_READY,
            ]
        )
    };
}

/// [`agree!`] over every register of the AX-12A's map (`dynamixel1`), listed once.
macro_rules! agree_ax12 {
    ($window:expr, $codec:expr) => {
        agree!(
            dynamixel1,
            $window,
            $codec,
            [
                MODEL_NUMBER,
                FIRMWARE_VERSION,
                ID,
                BAUD_RATE,
                RETURN_DELAY_TIME,
                CW_ANGLE_LIMIT,
                CCW_ANGLE_LIMIT,
                TEMPERATURE_LIMIT,
                MIN_VOLTAGE_LIMIT,
                MAX_VOLTAGE_LIMIT,
                MAX_TORQUE,
                STATUS_RETURN_LEVEL,
                ALARM_LED,
                SHUTDOWN,
                TORQUE_ENABLE,
                LED,
                CW_COMPLIANCE_MARGIN,
                CCW_COMPLIANCE_MARGIN,
                CW_COMPLIANCE_SLOPE,
                CCW_COMPLIANCE_SLOPE,
                GOAL_POSITION,
                MOVING_SPEED,
                TORQUE_LIMIT,
                PRESENT_POSITION,
                PRESENT_SPEED,
                PRESENT_LOAD,
                PRESENT_VOLTAGE,
                PRESENT_TEMPERATURE,
                REGISTERED,
                MOVING,
                LOCK,
                PUNCH,
            ]
        )
    };
}

/// Bytes that differ from run to run (a linear congruential sequence).
fn bytes(seed: u32, n: usize) -> Vec<u8> {
    let mut x = seed.wrapping_mul(2_654_435_761).wrapping_add(1);
    (0..n)
        .map(|_| {
            x = x.wrapping_mul(1_103_515_245).wrapping_add(12_345);
            (x >> 16) as u8
        })
        .collect()
}

/// The codec's registers of each frame of `wire`, heard in order as one conversation by the
/// codec of spec `name` (each spec loaded once).
fn hear(name: &str, wire: &[Vec<u8>]) -> Vec<Option<RegisterValues>> {
    static PROTOCOL2: OnceLock<Interpreter> = OnceLock::new();
    static PROTOCOL1: OnceLock<Interpreter> = OnceLock::new();
    let cell = if name == "dynamixel" {
        &PROTOCOL2
    } else {
        &PROTOCOL1
    };
    let i = cell.get_or_init(|| interpreter(name));
    let codec = i.codec();
    let mut c = Conversation::new();
    wire.iter()
        .map(|f| {
            let d = codec.decode_frame(0, f);
            let heard = c.hear(&codec, 0, f, None, d);
            assert!(heard.decoded.is_ok(), "{:?}", heard.decoded);
            heard.registers
        })
        .collect()
}

/// The note says what is not whole registers exactly when the bytes are not all whole
/// registers' or the answer is shorter than asked.
fn check_note(codec: &RegisterValues, window: Window<'_>, whole: usize, short: bool) {
    let complete = whole == window.bytes().len() && !short;
    assert_eq!(
        codec.note.is_none(),
        complete,
        "{window:?}: {:?}",
        codec.note
    );
}

mod protocol2 {
    use super::*;
    use dynamixel::{Header, Message, Packet, Read, Status, Write};

    fn frame(message: Message) -> Vec<u8> {
        let mut buf = vec![0u8; dynamixel::MAX_FRAME_LEN];
        let n = Packet {
            header: Header { id: 1 },
            message,
        }
        .encode(&mut buf)
        .expect("encodes");
        buf.truncate(n);
        buf
    }

    fn check(read: Read, status: &Status, codec: &RegisterValues) {
        let window = dynamixel::registers::read_answer(&read, status);
        let whole = agree_xm430!(window, codec);
        check_note(
            codec,
            window,
            whole,
            status.data.len() < usize::from(read.length),
        );
    }

    #[test]
    fn reads_of_every_range_agree_with_the_generated_accessors() {
        for address in 0..160u16 {
            for length in 1..=12u16 {
                let seed = u32::from(address) << 8 | u32::from(length);
                // Every third answer falls one byte short of what was asked.
                let n = usize::from(length) - usize::from(seed % 3 == 0);
                let read = Read { address, length };
                let status = Status {
                    data: Bytes::from_slice(&bytes(seed, n)).expect("fits"),
                    ..Status::default()
                };
                let heard = hear(
                    "dynamixel",
                    &[frame(Message::Read(read)), frame(Message::Status(status))],
                );
                assert_eq!(heard[0], None, "a READ carries no register values");
                let codec = heard[1].as_ref().expect("the status answers the READ");
                check(read, &status, codec);
            }
        }
    }

    #[test]
    fn writes_agree_with_the_generated_accessors() {
        for address in 0..160u16 {
            let write = Write {
                address,
                data: Bytes::from_slice(&bytes(u32::from(address), 6)).expect("fits"),
            };
            let heard = hear("dynamixel", &[frame(Message::Write(write))]);
            let codec = heard[0].as_ref().expect("a WRITE writes registers");
            let window = dynamixel::registers::write_data(&write);
            let whole = agree_xm430!(window, codec);
            check_note(codec, window, whole, false);
        }
    }

    #[test]
    fn a_read_of_present_position_gives_its_value() {
        let read = Read {
            address: 132,
            length: 4,
        };
        let status = Status {
            data: Bytes::from_slice(&2048i32.to_le_bytes()).expect("fits"),
            ..Status::default()
        };
        let heard = hear(
            "dynamixel",
            &[frame(Message::Read(read)), frame(Message::Status(status))],
        );
        let codec = heard[1].as_ref().expect("registers");
        assert_eq!(
            codec.values.get("present_position"),
            Some(&Value::Int(2048))
        );
        assert_eq!(codec.values.len(), 1);
        assert_eq!(codec.note, None);
        let window = dynamixel::registers::read_answer(&read, &status);
        assert_eq!(
            dynamixel::registers::PRESENT_POSITION.read(window),
            Some(2048)
        );
    }
}

mod protocol1 {
    use super::*;
    use dynamixel1::{Header, Message, Packet, Read, Request, Status, Write};

    fn frame(message: Message) -> Vec<u8> {
        let mut buf = vec![0u8; dynamixel1::MAX_FRAME_LEN];
        let n = Packet {
            header: Header { id: 1 },
            message,
        }
        .encode(&mut buf)
        .expect("encodes");
        buf.truncate(n);
        buf
    }

    #[test]
    fn reads_of_every_range_agree_with_the_generated_accessors() {
        for address in 0..52u8 {
            for length in 1..=8u8 {
                let seed = u32::from(address) << 8 | u32::from(length);
                let n = usize::from(length) - usize::from(seed % 3 == 0);
                let read = Read { address, length };
                let status = Status {
                    params: Bytes::from_slice(&bytes(seed, n)).expect("fits"),
                    ..Status::default()
                };
                let heard = hear(
                    "dynamixel1",
                    &[
                        frame(Message::Request(Request::Read(read))),
                        frame(Message::Response(status)),
                    ],
                );
                let codec = heard[1].as_ref().expect("the status answers the READ");
                let window = dynamixel1::registers::read_answer(&read, &status);
                let whole = agree_ax12!(window, codec);
                check_note(codec, window, whole, n < usize::from(length));
            }
        }
    }

    #[test]
    fn writes_agree_with_the_generated_accessors() {
        for address in 0..52u8 {
            let write = Write {
                address,
                data: Bytes::from_slice(&bytes(u32::from(address), 5)).expect("fits"),
            };
            let heard = hear(
                "dynamixel1",
                &[frame(Message::Request(Request::Write(write)))],
            );
            let codec = heard[0].as_ref().expect("a WRITE writes registers");
            let window = dynamixel1::registers::write_data(&write);
            let whole = agree_ax12!(window, codec);
            check_note(codec, window, whole, false);
        }
    }
}
