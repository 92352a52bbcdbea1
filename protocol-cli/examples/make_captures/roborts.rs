//! RoboMaster RoboRTS SDK: the onboard computer and the chassis and gimbal boards.

use crate::{Stream, wave};

protocol_kit::protocol!("../specs/roborts.toml");

/// 1 s of the SDK link at 50 Hz: speed and gimbal commands from the onboard computer (0x00),
/// chassis (0x01) and gimbal (0x02) state, forwarded referee power data at 10 Hz, a heartbeat
/// every 0.5 s that needs an acknowledgement (answered with a bare header), the chassis
/// parameters once, and a frame of a command set this spec does not have.
pub fn capture() -> Stream {
    use roborts::*;
    let mut s = Stream::new(0x524F_424F_5254_0005, &[0xAA]);
    fn send(s: &mut Stream, header: Header, message: Message) {
        let mut buf = [0u8; MAX_FRAME_LEN];
        let n = Packet { header, message }
            .encode(&mut buf)
            .expect("encodes");
        s.frame(&buf[..n]);
    }
    let mut seqs = [0u16; 3];
    let mut header = |from: u8, to: u8, session_id: u8| {
        let seq_num = seqs[usize::from(from)];
        seqs[usize::from(from)] = seq_num.wrapping_add(1);
        Header {
            session_id,
            sender: from,
            receiver: to,
            seq_num,
        }
    };
    let (mut x, mut angle) = (0i32, 0i16);
    for tick in 0..50u16 {
        let t = f32::from(tick) * 0.02;
        let vx = (1500.0 * (t * 2.0).min(1.0)) as i16;
        let vw = (300.0 * wave(t, 1.0)) as i16;
        send(
            &mut s,
            header(0, 1, 0),
            Message::SetChassisSpeed(ChassisSpeed {
                vx,
                vy: 0,
                vw,
                rotate_x_offset: 0,
                rotate_y_offset: 0,
            }),
        );
        send(
            &mut s,
            header(0, 2, 0),
            Message::SetGimbalAngle(GimbalAngle {
                yaw_mode: AngleMode::Relative,
                pitch_mode: AngleMode::Absolute,
                pitch: -50,
                yaw: (120.0 * wave(t, 0.8)) as i16,
            }),
        );
        x += i32::from(vx) / 50;
        angle = angle.wrapping_add(vw / 50);
        let gyro_rate = vw + s.rng.jitter(20.0) as i16;
        let v_x_mm = vx + s.rng.jitter(15.0) as i16;
        let v_y_mm = s.rng.jitter(5.0) as i16;
        send(
            &mut s,
            header(1, 0, 0),
            Message::PushChassisInfo(ChassisInfo {
                gyro_angle: angle,
                gyro_rate,
                position_x_mm: x,
                position_y_mm: 0,
                angle_deg: angle / 10,
                v_x_mm,
                v_y_mm,
            }),
        );
        send(
            &mut s,
            header(2, 0, 0),
            Message::PushGimbalInfo(GimbalInfo {
                mode: 1,
                pitch_ecd_angle: -50,
                yaw_ecd_angle: (120.0 * wave(t - 0.02, 0.8)) as i16,
                pitch_gyro_angle: -48,
                yaw_gyro_angle: angle,
                yaw_rate: vw,
                pitch_rate: 0,
            }),
        );
        if tick % 5 == 0 {
            let current = 1800 + s.rng.below(300) as u16;
            send(
                &mut s,
                header(1, 0, 0),
                Message::RobotPowerHeat(PowerHeatData {
                    chassis_volt: 24_000,
                    chassis_current: current,
                    chassis_power: 24.0 * f32::from(current) / 1000.0,
                    chassis_power_buffer: 60,
                    shooter_heat0: 0,
                    shooter_heat1: 0,
                }),
            );
        }
        if tick % 25 == 10 {
            // A heartbeat in session 2 (acknowledgement required), and its acknowledgement:
            // the bare header, with the heartbeat's session and sequence number.
            let beat = header(0, 1, 2);
            send(
                &mut s,
                beat,
                Message::Heartbeat(Heartbeat {
                    heartbeat: u32::from(tick),
                }),
            );
            let ack = Header {
                session_id: 2,
                sender: 1,
                receiver: 0,
                seq_num: beat.seq_num,
            };
            send(&mut s, ack, Message::Ack(protocol_kit::Bytes::new()));
        }
        if tick == 3 {
            send(
                &mut s,
                header(1, 0, 0),
                Message::GetChassisParam(ChassisParam {
                    wheel_perimeter: 478,
                    wheel_track: 403,
                    wheel_base: 385,
                    gimbal_x_offset: 0,
                    gimbal_y_offset: 0,
                }),
            );
        }
        if tick == 42 {
            // Command set 0x05 of a later SDK, which this spec does not have.
            let mut frame = [0u8; 12 + 2 + 4 + 4];
            let len = frame.len() as u16;
            frame[1..3].copy_from_slice(&len.to_le_bytes());
            frame[4] = 0x01;
            frame[12] = 0x01;
            frame[13] = 0x05;
            frame[14..18].copy_from_slice(&[0x10, 0x20, 0x30, 0x40]);
            LAYOUT.seal(&mut frame).expect("seals");
            s.unknown(&frame);
        }
    }
    s
}
