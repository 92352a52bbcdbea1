//! The parameters of a spec's CRC as the `crc` crate takes them (`&'static`), for the tests'
//! oracles: a CRC by that crate's own implementation, independent of the runtime's tables.
//!
//! The codecs hold their CRC parameters by value; the `crc` crate borrows them for the whole
//! program, so the tests keep one copy per distinct parameter set (a test process meets a few
//! dozen).

use std::sync::Mutex;

/// A CRC width whose parameter sets [`params`] keeps.
pub trait Keep: crc::Width + PartialEq + Copy + Send + 'static {
    /// The kept copy of `p`.
    fn keep(p: &crc::Algorithm<Self>) -> &'static crc::Algorithm<Self>;
}

macro_rules! keep_width {
    ($($w:ty),*) => {$(
        impl Keep for $w {
            fn keep(p: &crc::Algorithm<$w>) -> &'static crc::Algorithm<$w> {
                static KEPT: Mutex<Vec<&'static crc::Algorithm<$w>>> = Mutex::new(Vec::new());
                let mut kept = KEPT.lock().unwrap_or_else(|e| e.into_inner());
                if let Some(found) = kept.iter().find(|a| ***a == *p) {
                    return found;
                }
                let leaked: &'static crc::Algorithm<$w> = Box::leak(Box::new(*p));
                kept.push(leaked);
                leaked
            }
        }
    )*};
}
keep_width!(u8, u16, u32, u64);

/// `p`, for `crc::Crc::new`.
pub fn params<W: Keep>(p: &crc::Algorithm<W>) -> &'static crc::Algorithm<W> {
    W::keep(p)
}
