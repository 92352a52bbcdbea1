//! Periodic commands on a simulated clock, through generated code: the Scout host drives its
//! base every 20 ms (`periodic`), which keeps the base's watchdog (500 ms) from expiring until
//! the host stops; a MAVLink ground station and autopilot each send a HEARTBEAT once a second,
//! and the heartbeats expect no answer.

use protocol_kit::session::{Alarm, Sender};

protocol_kit::protocol!("../specs/scout.toml");
protocol_kit::protocol!("../specs/mavlink.toml");

fn motion() -> Vec<u8> {
    let packet = scout::Packet {
        header: scout::Header { count: 0 },
        message: scout::Message::MotionControl(scout::MotionControl::default()),
    };
    let mut buf = vec![0u8; scout::MAX_FRAME_LEN];
    let n = packet.encode(&mut buf).expect("encodes");
    buf.truncate(n);
    buf
}

/// The host sends what its scheduler says for `0..until` ms (stopping at `stop`), the base's
/// responder hears each frame at once: the instants sent and the watchdog's alarms.
fn drive(until: u64, stop: u64) -> (Vec<u64>, Vec<u64>) {
    let mut host = scout::Scheduler::new(scout::Session, Sender::Requester, 0);
    let mut base = scout::Responder::<4>::new(scout::Session);
    let key = scout::SESSION.periodic[0].key;
    let (mut sent, mut alarms) = (Vec::new(), Vec::new());
    for now in 0..until {
        while let Some(k) = host.poll(now) {
            assert_eq!(k, key);
            if now < stop {
                sent.push(now);
                base.on_frame(now, &motion());
            }
        }
        if base.poll(now) == Some(Alarm::WatchdogExpired) {
            alarms.push(now);
        }
    }
    (sent, alarms)
}

#[test]
fn the_scout_host_drives_at_50_hz_and_the_watchdog_holds_until_it_stops() {
    let (sent, alarms) = drive(2000, u64::MAX);
    assert_eq!(sent, (0..100).map(|i| i * 20).collect::<Vec<_>>());
    assert!(alarms.is_empty(), "{alarms:?}");
    // The host stops at 1000 ms: its last frame at 980 ms, the base stops at 1480 ms.
    let (sent, alarms) = drive(2000, 1000);
    assert_eq!(sent.last(), Some(&980));
    assert_eq!(alarms, [1480]);
    // The base sends nothing at a rate.
    let mut base = scout::Scheduler::new(scout::Session, Sender::Responder, 0);
    assert_eq!((base.poll(0), base.next_deadline()), (None, None));
}

#[test]
fn each_mavlink_side_sends_a_heartbeat_a_second_expecting_nothing() {
    let heartbeat = heartbeat_frame();
    for side in [Sender::Requester, Sender::Responder] {
        let mut s = mavlink::Scheduler::new(mavlink::Session, side, 500);
        let mut requester = mavlink::Requester::<2>::new(mavlink::Session);
        let mut at = Vec::new();
        for now in 0..10_000 {
            while let Some(k) = s.poll(now) {
                assert_eq!(k, 0, "HEARTBEAT's id");
                at.push(now);
                let mut frame = heartbeat.clone();
                assert_eq!(requester.send(now, &mut frame), Ok(None));
            }
        }
        assert_eq!(at, (0..10).map(|i| 500 + i * 1000).collect::<Vec<_>>());
        assert_eq!(requester.open(), 0);
    }
}

fn heartbeat_frame() -> Vec<u8> {
    let packet = mavlink::Packet {
        header: mavlink::Header::default(),
        message: mavlink::Message::Heartbeat(mavlink::Heartbeat::default()),
    };
    let mut buf = vec![0u8; mavlink::MAX_FRAME_LEN];
    let n = packet.encode(&mut buf).expect("encodes");
    buf.truncate(n);
    buf
}
