// A MAVLink node that uses three messages, included by every binary: it reads the MAVLink 2
// frames that arrive, keeps the attitude and position of ATTITUDE and GLOBAL_POSITION_INT
// frames, and answers each HEARTBEAT with one of its own. Every other message is dropped.
//
// `three_messages!(module, from_frame)` decodes each frame with `Packet::from_frame` (every
// message of the spec), matches the message and answers with `Packet::encode`;
// `three_messages!(module, from_frame_as)` decodes it with `Packet::from_frame_as` for each of
// the three messages alone and answers with `Packet::encode_as`;
// `three_messages!(module, handler)` decodes it with `Packet::from_frame` and hands it to a
// `Handler` that writes the three methods (`dispatch`), answering with `Packet::encode`.
//
// The received bytes come from `black_box`, so nothing is constant folded.

macro_rules! three_messages {
    ($module:ident, $receive:ident) => {
        use $module::{Attitude, GlobalPositionInt, Header, Heartbeat, Message, Packet};

        #[panic_handler]
        fn panic(_: &core::panic::PanicInfo<'_>) -> ! {
            loop {
                core::hint::spin_loop();
            }
        }

        /// Keeps the attitude.
        fn attitude(a: &Attitude) {
            core::hint::black_box((a.roll, a.pitch, a.yaw));
        }

        /// Keeps the position.
        fn position(p: &GlobalPositionInt) {
            core::hint::black_box((p.lat, p.lon, p.alt));
        }

        /// This node's HEARTBEAT header.
        fn header(seq: &mut u8) -> Header {
            let header = Header {
                seq: *seq,
                sysid: 1,
                compid: 1,
                ..Header::default()
            };
            *seq = seq.wrapping_add(1);
            header
        }

        /// Answers a HEARTBEAT with one of this node's, as a `Packet`.
        #[allow(dead_code)]
        fn answer(h: &Heartbeat, seq: &mut u8, out: &mut [u8]) {
            let reply = Packet {
                header: header(seq),
                message: Message::Heartbeat(Heartbeat {
                    custom_mode: 0,
                    ..*h
                }),
            };
            if let Ok(n) = reply.encode(out) {
                core::hint::black_box(&out[..n]);
            }
        }

        /// Answers a HEARTBEAT with one of this node's, as the struct alone.
        #[allow(dead_code)]
        fn answer_as(h: &Heartbeat, seq: &mut u8, out: &mut [u8]) {
            let reply = Heartbeat {
                custom_mode: 0,
                ..*h
            };
            if let Ok(n) = Packet::encode_as(&header(seq), &reply, out) {
                core::hint::black_box(&out[..n]);
            }
        }

        /// Every message of the spec decoded, then matched.
        #[allow(dead_code)]
        fn from_frame(frame: &[u8], seq: &mut u8, out: &mut [u8]) {
            let Ok(packet) = Packet::from_frame(frame) else {
                return;
            };
            match packet.message {
                Message::Attitude(a) => attitude(&a),
                Message::GlobalPositionInt(p) => position(&p),
                Message::Heartbeat(h) => answer(&h, seq, out),
                _ => {}
            }
        }

        /// Each of the three messages decoded alone.
        #[allow(dead_code)]
        fn from_frame_as(frame: &[u8], seq: &mut u8, out: &mut [u8]) {
            if let Ok(Some((_, a))) = Packet::from_frame_as::<Attitude>(frame) {
                attitude(&a);
            } else if let Ok(Some((_, p))) = Packet::from_frame_as::<GlobalPositionInt>(frame) {
                position(&p);
            } else if let Ok(Some((_, h))) = Packet::from_frame_as::<Heartbeat>(frame) {
                answer_as(&h, seq, out);
            }
        }

        /// The node as a `Handler`: the three methods it writes, every other one the
        /// default, which ignores the message.
        struct Node<'o> {
            seq: u8,
            out: &'o mut [u8],
        }

        impl $module::Handler for Node<'_> {
            fn heartbeat(&mut self, _: &Header, h: &Heartbeat) {
                answer(h, &mut self.seq, self.out);
            }
            fn attitude(&mut self, _: &Header, a: &Attitude) {
                attitude(a);
            }
            fn global_position_int(&mut self, _: &Header, p: &GlobalPositionInt) {
                position(p);
            }
        }

        /// Every message of the spec decoded, then handed to the handler (`dispatch`).
        #[allow(dead_code)]
        fn handler(frame: &[u8], seq: &mut u8, out: &mut [u8]) {
            let Ok(packet) = Packet::from_frame(frame) else {
                return;
            };
            let mut node = Node { seq: *seq, out };
            // A HEARTBEAT's answer is sent by the method: `dispatch` returns none.
            let _ = $module::dispatch(&mut node, &packet);
            *seq = node.seq;
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
                    $receive(frame.bytes, &mut seq, &mut out);
                }
            }
        }
    };
}
