//! The session's requester on an async UART, as firmware holds it: `session::io_async::Link`
//! over concrete `embedded-io-async` types and a clock, its request future polled, so that the
//! whole loop (read, deadline, retry) is compiled for the target, not only type-checked.

use core::convert::Infallible;
use core::future::Future;
use core::pin::pin;
use core::task::{Context, Poll, Waker};

use protocol_kit::embedded_io_async::{ErrorType, Read, Write};
use protocol_kit::session::io_async::{Clock, Link, LinkError, Reply};

use crate::hflink;

/// A UART whose driver has nothing to read yet and takes every byte written.
#[derive(Debug)]
pub struct Uart;

impl ErrorType for Uart {
    type Error = Infallible;
}

impl Read for Uart {
    async fn read(&mut self, _buf: &mut [u8]) -> Result<usize, Infallible> {
        core::future::pending().await
    }
}

impl Write for Uart {
    async fn write(&mut self, buf: &[u8]) -> Result<usize, Infallible> {
        Ok(buf.len())
    }

    async fn flush(&mut self) -> Result<(), Infallible> {
        Ok(())
    }
}

/// A millisecond counter that a timer interrupt would advance.
#[derive(Debug)]
pub struct Ticks(pub u64);

impl Clock for Ticks {
    fn now_ms(&self) -> u64 {
        self.0
    }

    fn wait_until(&mut self, at: u64) -> impl Future<Output = ()> {
        self.0 = self.0.max(at);
        core::future::ready(())
    }
}

/// HFLink's requester on the UART: 2 open requests, a read buffer of 32 bytes.
pub type HflinkLink = Link<
    hflink::Session,
    Uart,
    Uart,
    Ticks,
    2,
    { hflink::MAX_FRAME_LEN },
    { hflink::DECODER_BUFFER_LEN },
    32,
>;

/// A link of HFLink's session.
pub fn hflink_link() -> HflinkLink {
    Link::new(hflink::Session, Uart, Uart, Ticks(0))
}

/// Polls the request of `frame` once, as an executor would on a UART interrupt.
pub fn poll_request(
    link: &mut HflinkLink,
    frame: &mut [u8],
    answer: &mut [u8],
) -> Poll<Result<Reply, LinkError<Infallible, Infallible>>> {
    let request = pin!(link.request(frame, answer, |_| {}));
    request.poll(&mut Context::from_waker(Waker::noop()))
}
