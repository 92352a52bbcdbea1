//! `Payload::from_bytes` checks the length first for the structs whose reading can fail only
//! for want of bytes (`READ_NEEDS_ONLY_BYTES`, set by the generator). That is a shortcut, not
//! a rule: it must give exactly what reading field by field gives (a value, or the same
//! `PayloadLength`), for every length, on every such struct of the bundled specs.

use protocol_kit::__private::Payload;

protocol_kit::protocol!("../specs/hflink.toml");
protocol_kit::protocol!("../specs/referee.toml");
protocol_kit::protocol!("../specs/scout.toml");

/// Compares both ways of reading on every length up to a few bytes past the size; returns
/// whether the type takes the shortcut.
fn same_either_way<T: Payload + PartialEq + std::fmt::Debug>(name: &str) -> bool {
    let mut state = 0x2545_F491_4F6C_DD1Du64;
    for len in 0..=T::SIZE + 4 {
        for _ in 0..64 {
            let bytes: Vec<u8> = (0..len)
                .map(|_| {
                    state ^= state << 13;
                    state ^= state >> 7;
                    state ^= state << 17;
                    state as u8
                })
                .collect();
            let (got, want) = (T::from_bytes(&bytes), T::read_exactly(&bytes));
            // Floats read from random bytes may be NaN, which is not equal to itself: compare
            // what was read, not the values.
            assert_eq!(
                format!("{got:?}"),
                format!("{want:?}"),
                "{name}, {len} bytes: {bytes:02x?}"
            );
        }
    }
    T::READ_NEEDS_ONLY_BYTES
}

macro_rules! check_all {
    ($($ty:path),* $(,)?) => {{
        let mut shortcut = 0;
        let mut total = 0;
        $(
            total += 1;
            shortcut += usize::from(same_either_way::<$ty>(stringify!($ty)));
        )*
        (shortcut, total)
    }};
}

#[test]
fn length_first_reads_what_field_by_field_reads() {
    let (shortcut, total) = check_all!(
        hflink::ChassisCoord,
        hflink::SystemInfo,
        hflink::ImuSensorData,
        hflink::GpsData,
        hflink::ChassisParameters,
        hflink::HeadParameters,
        hflink::MotorParameters,
        referee::GameState,
        referee::GameRobotState,
        referee::PowerHeatData,
        referee::GameRobotPos,
        referee::StudentInteractive,
        scout::MotionControl,
        scout::LightControl,
        scout::SystemStatus,
        scout::MotionStatus,
        scout::MotorDriverStatus,
    );
    // Most take the shortcut; the ones with enums or clamped values (Scout's) and variable
    // data (the referee's interactive frame) must not.
    assert_eq!((shortcut, total), (13, 17));
    const {
        assert!(!<scout::MotionControl as Payload>::READ_NEEDS_ONLY_BYTES);
        assert!(!<referee::StudentInteractive as Payload>::READ_NEEDS_ONLY_BYTES);
        assert!(<hflink::MotorParameters as Payload>::READ_NEEDS_ONLY_BYTES);
    }
}
