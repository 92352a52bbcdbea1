//! A random round trip between this project's codec and a peer, for any protocol.
//!
//! A protocol takes part by implementing [`PeerAdapter`] over a neutral message type of its
//! own: the values a message carries, in the protocol's terms, with no encoding of either side.
//! [`cross_check`] then draws messages from the adapter's strategy (proptest's deterministic
//! runner, so a run is reproducible) and, for each one:
//!
//! 1. the peer writes it, this project decodes the frame, and the values must be equal;
//! 2. this project writes it, the peer decodes the frame, and the values must be equal;
//! 3. when both sides wrote it, the two frames must be the same bytes.
//!
//! A peer often implements one side of a link only (a bus master writes instructions and reads
//! status packets): its adapter answers `None` for the kinds it cannot write or read, and the
//! [`Tally`] counts what was compared in each direction, so a test states what it covered.

use proptest::strategy::{BoxedStrategy, Strategy, ValueTree};
use proptest::test_runner::TestRunner;
use std::fmt::Debug;

/// One protocol's two codecs, seen through a neutral message type.
pub trait PeerAdapter {
    /// The values of one message, as the protocol documents them.
    type Message: Clone + Debug + PartialEq;

    /// The peer's name (crate and version), for reports.
    fn peer(&self) -> &'static str;

    /// The messages to draw from.
    fn messages(&self) -> BoxedStrategy<Self::Message>;

    /// The frame the peer writes for `message`, or `None` when the peer cannot write this kind.
    ///
    /// # Errors
    ///
    /// When the peer fails on a message it should write.
    fn peer_write(&mut self, message: &Self::Message) -> Result<Option<Vec<u8>>, String>;

    /// What the peer decodes from `frame`, or `None` when it cannot read this kind. `like` is the
    /// message the frame was written from, for peers that must be told what to expect (a reply's
    /// length); an adapter never copies values from it.
    ///
    /// # Errors
    ///
    /// When the peer rejects the frame.
    fn peer_read(
        &mut self,
        frame: &[u8],
        like: &Self::Message,
    ) -> Result<Option<Self::Message>, String>;

    /// The frame this project writes for `message`.
    ///
    /// # Errors
    ///
    /// When this project's encoder fails.
    fn ours_write(&self, message: &Self::Message) -> Result<Vec<u8>, String>;

    /// What this project decodes from `frame`.
    ///
    /// # Errors
    ///
    /// When this project's decoder rejects the frame.
    fn ours_read(&self, frame: &[u8]) -> Result<Self::Message, String>;
}

/// What [`cross_check`] compared.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Tally {
    /// Messages drawn.
    pub messages: usize,
    /// Frames written by the peer and decoded here to the same values.
    pub peer_to_ours: usize,
    /// Frames written here and decoded by the peer to the same values.
    pub ours_to_peer: usize,
    /// Messages both sides wrote, to the same bytes.
    pub same_bytes: usize,
}

/// Draws `cases` messages and runs the round trip of the module docs on each.
///
/// # Errors
///
/// The first disagreement, with the message, the frame and both sides' views.
pub fn cross_check<A: PeerAdapter>(adapter: &mut A, cases: usize) -> Result<Tally, String> {
    let strategy = adapter.messages();
    let mut runner = TestRunner::deterministic();
    let mut tally = Tally::default();
    for case in 0..cases {
        let message = strategy
            .new_tree(&mut runner)
            .map_err(|e| format!("drawing message {case}: {e}"))?
            .current();
        tally.messages += 1;
        let peer_frame = adapter.peer_write(&message)?;
        if let Some(frame) = &peer_frame {
            let ours = adapter
                .ours_read(frame)
                .map_err(|e| mismatch(adapter, case, &message, frame, "ours rejects", &e))?;
            if ours != message {
                let seen = format!("{ours:?}");
                return Err(mismatch(
                    adapter,
                    case,
                    &message,
                    frame,
                    "ours decodes",
                    &seen,
                ));
            }
            tally.peer_to_ours += 1;
        }
        let our_frame = adapter.ours_write(&message)?;
        let peer = adapter
            .peer_read(&our_frame, &message)
            .map_err(|e| mismatch(adapter, case, &message, &our_frame, "peer rejects", &e))?;
        if let Some(peer) = peer {
            if peer != message {
                let seen = format!("{peer:?}");
                return Err(mismatch(
                    adapter,
                    case,
                    &message,
                    &our_frame,
                    "peer decodes",
                    &seen,
                ));
            }
            tally.ours_to_peer += 1;
        }
        if let Some(frame) = peer_frame {
            if frame != our_frame {
                let seen = format!("{frame:02x?}");
                return Err(mismatch(
                    adapter,
                    case,
                    &message,
                    &our_frame,
                    "peer wrote",
                    &seen,
                ));
            }
            tally.same_bytes += 1;
        }
    }
    Ok(tally)
}

/// Runs [`cross_check`] on `cases` messages and asserts that every one crossed both ways and
/// that both sides wrote the same bytes for it; prints the tally under `label`.
///
/// # Panics
///
/// On the first disagreement, or when a message did not cross one way (the peer could not
/// write or read it).
pub fn assert_every_message_crosses<A: PeerAdapter>(
    adapter: &mut A,
    cases: usize,
    label: &str,
) -> Tally {
    let tally = cross_check(adapter, cases).unwrap_or_else(|e| panic!("{e}"));
    println!("{label}: {tally:?}");
    assert_eq!(tally.messages, cases, "{label}");
    assert_eq!(
        tally.peer_to_ours, cases,
        "{label}: every peer frame decodes here"
    );
    assert_eq!(
        tally.ours_to_peer, cases,
        "{label}: every frame written here decodes in the peer"
    );
    assert_eq!(
        tally.same_bytes, cases,
        "{label}: both sides write the same bytes"
    );
    tally
}

fn mismatch<A: PeerAdapter>(
    adapter: &A,
    case: usize,
    message: &A::Message,
    frame: &[u8],
    what: &str,
    seen: &str,
) -> String {
    format!(
        "{} case {case}: {message:?}\n  frame {frame:02x?}\n  {what}: {seen}",
        adapter.peer()
    )
}
