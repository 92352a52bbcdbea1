// A MAVLink node that uses three messages, included by both binaries: it reads the MAVLink 2
// frames that arrive, keeps the attitude and position of ATTITUDE and GLOBAL_POSITION_INT
// frames, and answers each HEARTBEAT with one of its own. Every other message is dropped.
//
// The received bytes come from `black_box`, so nothing is constant folded.

macro_rules! three_messages {
    ($module:ident) => {
        use $module::{Header, Heartbeat, Message, Packet};

        #[panic_handler]
        fn panic(_: &core::panic::PanicInfo<'_>) -> ! {
            loop {
                core::hint::spin_loop();
            }
        }

        #[cortex_m_rt::entry]
        fn main() -> ! {
            let mut decoder = $module::decoder();
            let mut out = [0u8; $module::MAX_FRAME_LEN];
            let mut seq = 0u8;
            loop {
                let rx = core::hint::black_box([0u8; 64]);
                let mut input = &rx[..];
                while let Some(frame) = decoder.decode(&mut input) {
                    let Ok(packet) = Packet::from_frame(frame.bytes) else {
                        continue;
                    };
                    match packet.message {
                        Message::Attitude(a) => {
                            core::hint::black_box((a.roll, a.pitch, a.yaw));
                        }
                        Message::GlobalPositionInt(p) => {
                            core::hint::black_box((p.lat, p.lon, p.alt));
                        }
                        Message::Heartbeat(h) => {
                            let reply = Packet {
                                header: Header {
                                    seq,
                                    sysid: 1,
                                    compid: 1,
                                    ..Header::default()
                                },
                                message: Message::Heartbeat(Heartbeat {
                                    custom_mode: 0,
                                    ..h
                                }),
                            };
                            seq = seq.wrapping_add(1);
                            if let Ok(n) = reply.encode(&mut out) {
                                core::hint::black_box(&out[..n]);
                            }
                        }
                        _ => {}
                    }
                }
            }
        }
    };
}
