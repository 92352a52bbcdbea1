//! `defmt::Format` (the `defmt` feature) for the runtime's value types, so that generated
//! types deriving it (`protocol!(..., derive(defmt))`) can be logged from firmware: [`Bytes`]
//! as hex bytes, [`FixedStr`] as its text when it is canonical (else its `N` bytes), [`NulStr`]
//! and [`Str`] as their text (their bytes when it is not UTF-8), [`Group`] as the list of its elements. The
//! errors and the decoder's events derive `Format` where they are declared.
//!
//! A value type added to the runtime gets its `Format` impl here, usually one `write!`.

use defmt::{Format, Formatter, write};

use crate::bytes::Bytes;
use crate::group::Group;
use crate::text::{FixedStr, NulStr};
use crate::unterminated::Str;

impl<const N: usize> Format for Bytes<N> {
    fn format(&self, f: Formatter<'_>) {
        write!(f, "{=[u8]:02x}", self.as_slice());
    }
}

impl<const N: usize> Format for FixedStr<N> {
    fn format(&self, f: Formatter<'_>) {
        match self.as_str() {
            Ok(text) if self.is_canonical() => write!(f, "{=str:?}", text),
            _ => write!(f, "{=[u8]:02x}", &self.as_bytes()[..]),
        }
    }
}

impl<const N: usize> Format for NulStr<N> {
    fn format(&self, f: Formatter<'_>) {
        match self.as_str() {
            Ok(text) => write!(f, "{=str:?}", text),
            Err(_) => write!(f, "{=[u8]:02x}", self.text()),
        }
    }
}

impl<const N: usize> Format for Str<N> {
    fn format(&self, f: Formatter<'_>) {
        match self.as_str() {
            Ok(text) => write!(f, "{=str:?}", text),
            Err(_) => write!(f, "{=[u8]:02x}", self.text()),
        }
    }
}

impl<T: Copy + Default + Format, const N: usize> Format for Group<T, N> {
    fn format(&self, f: Formatter<'_>) {
        write!(f, "{=[?]}", self.as_slice());
    }
}
