//! The RoboMaster referee system: what a robot's UART receives during a match.

use crate::{Stream, wave};

protocol_kit::protocol!("../specs/referee.toml");
protocol_kit::protocol!("../specs/referee2018.toml");

/// Referee system, 2019 table: what a robot's UART receives during 2 s of a match, at the
/// rates of the referee manual (power and heat 50 Hz, robot state and position 10 Hz, game
/// state, buffs and events 1 Hz), a shot every 100 ms, two hits, an interactive frame (0x0301)
/// from a teammate, and a frame of a later season's table (0x0209), which this spec does not
/// describe.
pub fn capture() -> Stream {
    use referee::*;
    let mut s = Stream::new(0x5245_4645_5245_0002, &[0xA5]);
    fn send(s: &mut Stream, seq: &mut u8, message: Message) {
        let mut buf = [0u8; MAX_FRAME_LEN];
        let n = Packet {
            header: Header { seq: *seq },
            message,
        }
        .encode(&mut buf)
        .expect("encodes");
        *seq = seq.wrapping_add(1);
        s.frame(&buf[..n]);
    }
    let mut seq = 0u8;
    let mut heat = 0u16;
    let mut hp = 600u16;
    for tick in 0..100u32 {
        let t = tick as f32 * 0.02;
        if tick % 50 == 0 {
            send(
                &mut s,
                &mut seq,
                Message::GameState(GameState {
                    game_type: 1,
                    game_progress: 4,
                    stage_remain_time: 180 - (tick / 50) as u16,
                }),
            );
            send(
                &mut s,
                &mut seq,
                Message::EventData(EventData {
                    event_type: 0b0000_0011,
                }),
            );
            send(
                &mut s,
                &mut seq,
                Message::BuffMusk(BuffMusk { power_rune_buff: 0 }),
            );
        }
        if tick % 5 == 0 {
            send(
                &mut s,
                &mut seq,
                Message::GameRobotState(GameRobotState {
                    robot_id: 3,
                    robot_level: 1,
                    remain_hp: hp,
                    max_hp: 600,
                    shooter_heat0_cooling_rate: 40,
                    shooter_heat0_cooling_limit: 240,
                    shooter_heat1_cooling_rate: 0,
                    shooter_heat1_cooling_limit: 0,
                    mains_power_gimbal_output: true,
                    mains_power_chassis_output: true,
                    mains_power_shooter_output: true,
                }),
            );
            send(
                &mut s,
                &mut seq,
                Message::GameRobotPos(GameRobotPos {
                    x: 2.0 + t * 0.8,
                    y: 3.5 + 0.3 * wave(t, 1.5),
                    z: 0.0,
                    yaw: 90.0 + 20.0 * wave(t, 2.0),
                }),
            );
            let bullet_speed = 14.8 + s.rng.jitter(0.3);
            send(
                &mut s,
                &mut seq,
                Message::ShootData(ShootData {
                    bullet_type: 1,
                    bullet_freq: 10,
                    bullet_speed,
                }),
            );
            heat = heat.saturating_add(10);
        }
        heat = heat.saturating_sub(1);
        let current = 2100 + (s.rng.below(400) as u16);
        send(
            &mut s,
            &mut seq,
            Message::PowerHeatData(PowerHeatData {
                chassis_volt: 24_100,
                chassis_current: current,
                chassis_power: 24.1 * current as f32 / 1000.0,
                chassis_power_buffer: 60,
                shooter_heat0: heat,
                shooter_heat1: 0,
            }),
        );
        if tick == 37 || tick == 81 {
            hp -= 10;
            send(
                &mut s,
                &mut seq,
                Message::RobotHurt(RobotHurt {
                    armor_id: (tick % 4) as u8,
                    hurt_type: 0,
                }),
            );
        }
        if tick == 60 {
            // Student interactive data (0x0301): content 0x0200 from robot 13 to robot 3.
            let data = protocol_kit::Bytes::from_slice(&[0x11, 0x22, 0x33, 0x44]).expect("fits");
            send(
                &mut s,
                &mut seq,
                Message::StudentInteractive(StudentInteractive {
                    data_cmd_id: 0x0200,
                    sender_id: 13,
                    receiver_id: 3,
                    data,
                }),
            );
        }
        if tick == 70 {
            // RFID status (0x0209) of the 2020 table, which this 2019 spec does not have.
            let data = [0x01, 0x00, 0x00, 0x00];
            let mut frame = vec![0u8; 7 + data.len() + 2];
            frame[3] = seq;
            frame[5..7].copy_from_slice(&0x0209u16.to_le_bytes());
            frame[7..7 + data.len()].copy_from_slice(&data);
            LAYOUT.seal(&mut frame).expect("seals");
            s.unknown(&frame);
        }
    }
    s
}

/// Referee system, 2018 table: 1 s of a robot's UART (power 50 Hz, game state and position
/// 10 Hz, a shot every 100 ms, one hit, one buff).
pub fn capture_2018() -> Stream {
    use referee2018::*;
    let mut s = Stream::new(0x5245_4632_3031_0008, &[0xA5]);
    fn send(s: &mut Stream, seq: &mut u8, message: Message) {
        let mut buf = [0u8; MAX_FRAME_LEN];
        let n = Packet {
            header: Header { seq: *seq },
            message,
        }
        .encode(&mut buf)
        .expect("encodes");
        *seq = seq.wrapping_add(1);
        s.frame(&buf[..n]);
    }
    let mut seq = 0x40u8;
    for tick in 0..50u32 {
        let t = tick as f32 * 0.02;
        if tick % 5 == 0 {
            send(
                &mut s,
                &mut seq,
                Message::GameInfo(GameRobotState {
                    stage_remain_time: 240 - (tick / 50) as u16,
                    game_process: 4,
                    reserved: 0,
                    remain_hp: if tick < 33 { 1500 } else { 1450 },
                    max_hp: 1500,
                }),
            );
            send(
                &mut s,
                &mut seq,
                Message::RobotPosData(RobotPosition {
                    x: 1.0 + t,
                    y: 2.0,
                    z: 0.0,
                    yaw: 45.0 + 10.0 * wave(t, 1.0),
                }),
            );
            let bullet_spd = 22.5 + s.rng.jitter(0.5);
            send(
                &mut s,
                &mut seq,
                Message::RealShootData(RealShoot {
                    bullet_type: 1,
                    bullet_freq: 10,
                    bullet_spd,
                }),
            );
        }
        let current = 1.8 + s.rng.jitter(0.2);
        send(
            &mut s,
            &mut seq,
            Message::RealPowerData(RealPowerData {
                chassis_volt: 24.0,
                chassis_current: current,
                chassis_power: 24.0 * current,
                chassis_pwr_buf: 60.0,
                shooter1_heat: (tick * 3 % 90) as u16,
                shooter2_heat: 0,
            }),
        );
        if tick == 33 {
            send(
                &mut s,
                &mut seq,
                Message::RealBloodData(RobotHurt {
                    armor_type: 2,
                    hurt_type: 0,
                }),
            );
        }
        if tick == 40 {
            send(
                &mut s,
                &mut seq,
                Message::GainBuff(GetBuff { buff_musk: 0b0100 }),
            );
        }
    }
    s
}
