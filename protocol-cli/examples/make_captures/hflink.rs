//! HFLink: a host and a robot controller at 20 Hz.

use crate::{Stream, wave};

protocol_kit::protocol!("../specs/hflink.toml");

/// HFLink: a host (0x01) drives a robot controller (0x11) at 20 Hz for 2 s: speed commands
/// and their acknowledgements, measured speed and pose, IMU at 2 Hz, system info at 1 Hz, one
/// GPS fix; both directions of the link in one capture, as a sniffer on the wire sees them.
pub fn capture() -> Stream {
    use hflink::*;
    let mut s = Stream::new(0x4846_4C49_4E4B_0001, &[0xFF]);
    let host = Header {
        sender: 0x01,
        receiver: 0x11,
    };
    let robot = Header {
        sender: 0x11,
        receiver: 0x01,
    };
    fn send(s: &mut Stream, header: Header, message: Message) {
        let mut buf = [0u8; MAX_FRAME_LEN];
        let n = Packet { header, message }
            .encode(&mut buf)
            .expect("encodes");
        s.frame(&buf[..n]);
    }
    send(
        &mut s,
        host,
        Message::Request(Request::ShakingHands(ChassisCoord {
            x: 0.0,
            y: 0.0,
            z: 0.0,
        })),
    );
    let (mut x, mut y, mut heading) = (0.0f32, 0.0f32, 0.0f32);
    for cycle in 0..40u32 {
        let t = cycle as f32 * 0.05;
        let speed = ChassisCoord {
            x: 0.4,
            y: 0.0,
            z: 0.25 * wave(t, 2.0),
        };
        send(
            &mut s,
            host,
            Message::Request(Request::SetRobotSpeed(speed)),
        );
        send(&mut s, robot, Message::Response(Response::SetRobotSpeed));
        send(&mut s, host, Message::Request(Request::ReadRobotSpeed));
        let measured = ChassisCoord {
            x: speed.x + s.rng.jitter(0.02),
            y: s.rng.jitter(0.005),
            z: speed.z + s.rng.jitter(0.01),
        };
        send(
            &mut s,
            robot,
            Message::Response(Response::ReadRobotSpeed(measured)),
        );
        // Dead reckoning with a small-angle step: exact arithmetic, no trigonometry.
        heading += measured.z * 0.05;
        x += measured.x * 0.05 * (1.0 - heading * heading / 2.0);
        y += measured.x * 0.05 * heading;
        send(
            &mut s,
            host,
            Message::Request(Request::ReadGlobalCoordinate),
        );
        send(
            &mut s,
            robot,
            Message::Response(Response::ReadGlobalCoordinate(ChassisCoord {
                x,
                y,
                z: heading,
            })),
        );
        if cycle % 10 == 5 {
            send(&mut s, host, Message::Request(Request::ReadImuFusionData));
            let imu = ImuSensorData {
                pitch: s.rng.jitter(0.01),
                roll: s.rng.jitter(0.01),
                yaw: heading,
                bar_altitude: 12.5 + s.rng.jitter(0.2),
                magnetic_angle: 1.2 + heading,
            };
            send(
                &mut s,
                robot,
                Message::Response(Response::ReadImuFusionData(imu)),
            );
        }
        if cycle % 20 == 0 {
            send(&mut s, host, Message::Request(Request::ReadSystemInfo));
            let info = SystemInfo {
                system_time: 120.0 + t,
                cpu_temperature: 41.5 + s.rng.jitter(0.5),
                cpu_usage: 0.31 + s.rng.jitter(0.05),
                battery_voltage: 12.3 - t * 0.01,
                power_remain: 78.0,
            };
            send(
                &mut s,
                robot,
                Message::Response(Response::ReadSystemInfo(info)),
            );
        }
        if cycle == 17 {
            send(&mut s, host, Message::Request(Request::ReadGpsData));
            let gps = GpsData {
                utc_time: UtcTime {
                    year: 2017,
                    month: 3,
                    date: 14,
                    hour: 9,
                    min: 26,
                    sec: 53,
                },
                satellite_num: 9,
                altitude: 45.2,
                ground_speed: 0.39,
                latitude: 2_232_512,
                nshemi: b'N',
                longitude: 11_405_778,
                ewhemi: b'E',
            };
            send(&mut s, robot, Message::Response(Response::ReadGpsData(gps)));
        }
        if cycle == 30 {
            // A firmware extension the spec does not know: command 0x30 with two bytes.
            let mut frame = [0xFF, 0xFF, 0x11, 0x01, 0x00, 0x03, 0x30, 0x01, 0x02, 0x00];
            LAYOUT.seal(&mut frame).expect("seals");
            s.unknown(&frame);
        }
    }
    s
}
