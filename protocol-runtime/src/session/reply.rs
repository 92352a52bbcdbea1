//! What a generated handler answers a request with: the typed answer the spec's `[session]`
//! says the request expects (an acknowledgement is `Reply::ACK`), or a refusal. The generated
//! `dispatch` turns it into the answer packet; this module holds only the choice.

/// A handler's answer to a request that expects one.
///
/// `T` is the answer's payload: the reply's struct, the answering command's struct, or `()`
/// for an empty answer and for an acknowledgement.
///
/// ```
/// use protocol_runtime::session::Reply;
///
/// let temperature: Reply<u16> = Reply::Answer(41);
/// assert_eq!(temperature.answer(), Some(41));
/// assert_eq!(Reply::<()>::ACK, Reply::Answer(()));
/// assert_eq!(Reply::<u16>::Refuse.answer(), None);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Reply<T> {
    /// Answer the request with this.
    Answer(T),
    /// Refuse the request: the spec's `nack` command answers it when that command carries no
    /// payload in the answer's direction; otherwise nothing is sent and the requester times
    /// out. A handler's default for every request it does not implement.
    Refuse,
}

impl Reply<()> {
    /// The acknowledgement (an empty answer).
    pub const ACK: Self = Reply::Answer(());
}

impl<T> Reply<T> {
    /// The answer, `None` for a refusal.
    pub fn answer(self) -> Option<T> {
        match self {
            Reply::Answer(t) => Some(t),
            Reply::Refuse => None,
        }
    }
}
