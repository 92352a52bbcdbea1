//! AgileX Scout: the same traffic on the UART and on CAN.

use std::fmt::Write as _;

use protocol_cli::candump::format_log;

use crate::{Rng, Stream, hex};

protocol_kit::protocol!("../specs/scout.toml");

/// Scout status and commands for 1 s: the PC sends motion commands at 50 Hz, the base reports
/// motion at 50 Hz, its system, motor drivers and lights at 10 Hz. One capture of the UART
/// and one `candump -L` log of the same traffic on CAN.
pub fn captures() -> (Stream, String, String, String) {
    use scout::*;
    let mut s = Stream::new(0x5343_4F55_5400_0003, &[0x5A, 0xA5]);
    let mut can_log = String::new();
    let mut can_truth = String::new();
    let mut can_rng = Rng(0x5343_4F55_5400_0004);
    let mut buf = [0u8; MAX_FRAME_LEN];
    let mut counts = [0usize; 4];
    let mut count = 0u8;
    let mut log_index = 0usize;
    let mut time_us = 1_700_000_000_000_000u64;
    for tick in 0..50u32 {
        let t = tick as f32 * 0.02;
        let mut messages = vec![
            Message::MotionControl(MotionControl {
                control_mode: ControlMode::CmdUart,
                fault_clear_flag: FaultClear::None,
                linear_velocity: 0.6,
                angular_velocity: 0.10470,
                reserved0: 0,
                reserved1: 0,
            }),
            Message::MotionStatus(MotionStatus {
                linear_velocity: 0.6 * (t * 4.0).min(1.0),
                angular_velocity: 0.105,
                reserved: 0,
            }),
        ];
        if tick % 5 == 0 {
            messages.push(Message::SystemStatus(SystemStatus {
                base_state: BaseState::Normal,
                control_mode: ControlMode::CmdUart,
                battery_voltage: 26.4,
                bat_under_vol_f: false,
                bat_over_vol_f: false,
                motor1_comm_f: false,
                motor2_comm_f: false,
                motor3_comm_f: false,
                motor4_comm_f: false,
                motor_drv_overheat_f: false,
                motor_overcurrent_f: false,
                can_checksum_error: false,
                motor_drv_overheat_w: false,
                motor_overcurrent_w: false,
                bat_under_vol_w: tick > 40,
                rc_signal_loss: false,
            }));
            for (i, rpm) in [812i16, -809, -811, 810].into_iter().enumerate() {
                let status = MotorDriverStatus {
                    current: 1.5 + i as f32 * 0.1,
                    rpm,
                    temperature: 34,
                    reserved: 0,
                };
                messages.push(match i {
                    0 => Message::Motor1DriverStatus(status),
                    1 => Message::Motor2DriverStatus(status),
                    2 => Message::Motor3DriverStatus(status),
                    _ => Message::Motor4DriverStatus(status),
                });
            }
        }
        if tick % 25 == 0 {
            messages.push(Message::LightStatus(LightStatus {
                light_ctrl_enable: true,
                front_light_mode: LightMode::ConstOn,
                front_light_custom: 0,
                rear_light_mode: LightMode::Breath,
                rear_light_custom: 0,
                reserved: 0,
            }));
        }
        for message in messages {
            let header = Header { count };
            let n = Packet { header, message }
                .encode(&mut buf)
                .expect("encodes");
            s.frame(&buf[..n]);
            let can = CanPacket {
                header: CanHeader { count },
                message,
            }
            .encode()
            .expect("encodes");
            let mut data = can.data().to_vec();
            let kind = if can_rng.chance(3) {
                // A bit flip on the bus: the Scout checksum catches it.
                let at = can_rng.below(data.len() as u64) as usize;
                data[at] ^= 1 << can_rng.below(8);
                counts[1] += 1;
                "bad_checksum"
            } else {
                counts[0] += 1;
                "frame"
            };
            let time = format!("{}.{:06}", time_us / 1_000_000, time_us % 1_000_000);
            let _ = writeln!(
                can_log,
                "{}",
                format_log(&time, "can0", can.id, false, &data)
            );
            let _ = writeln!(
                can_truth,
                "{{\"offset\":{log_index},\"kind\":\"{kind}\",\"can_id\":{},\"hex\":\"{}\"}}",
                can.id,
                hex(&data)
            );
            log_index += 1;
            time_us += 1_000;
            count = count.wrapping_add(1);
        }
        if tick == 20 {
            // Odometry (0x311) of newer firmware, with the Scout checksum: unknown to this v1 spec.
            let time = format!("{}.{:06}", time_us / 1_000_000, time_us % 1_000_000);
            let mut virt = [0u8; 13];
            virt[..4].copy_from_slice(&0x311u32.to_be_bytes());
            virt[5..11].copy_from_slice(&[0x00, 0x00, 0x02, 0x6C, 0x00, 0x00]);
            virt[11] = count;
            CAN_LAYOUT.seal(&mut virt).expect("seals");
            let data = &virt[5..];
            let _ = writeln!(can_log, "{}", format_log(&time, "can0", 0x311, false, data));
            let _ = writeln!(
                can_truth,
                "{{\"offset\":{log_index},\"kind\":\"unknown_command\",\"can_id\":{},\"hex\":\"{}\"}}",
                0x311,
                hex(data)
            );
            log_index += 1;
            counts[2] += 1;
        }
        time_us += 20_000 - (time_us % 20_000);
    }
    let can_summary = format!(
        "{log_index} CAN frames: {} intact, {} with a flipped bit, {} of newer firmware",
        counts[0], counts[1], counts[2]
    );
    (s, can_log, can_truth, can_summary)
}
