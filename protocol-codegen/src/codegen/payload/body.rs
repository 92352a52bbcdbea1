//! The statements of one struct's `write` and `read`, field by field in wire order; each field
//! kind adds its own ([`Kind::body`]).

use proc_macro2::{Ident, TokenStream};
use quote::{format_ident, quote};

use super::kinds::{Kind, Slot};
use super::scalar::local;

/// The code of one struct's `write` and `read`, field by field in wire order.
#[derive(Default)]
pub(crate) struct Body {
    /// Statements of `write`.
    pub(crate) writes: Vec<TokenStream>,
    /// Statements of `read` before the value is built.
    pub(crate) reads: Vec<TokenStream>,
    /// `field: expression` of the value `read` builds.
    pub(crate) inits: Vec<TokenStream>,
    /// Statements of `read` after the value is built (trailing padding).
    pub(crate) after: Vec<TokenStream>,
    /// Whether a read expression needs an earlier field (sized bytes, groups), a statement
    /// comes between fields (a bit word) or padding comes before a field that is read in more
    /// than one step (an array): then every field is read into a local first.
    pub(crate) sequenced: bool,
}

impl Body {
    pub(super) fn of(slots: &[Slot<'_>], rt: &TokenStream) -> Body {
        let mut b = Body::default();
        for (i, f) in slots.iter().enumerate() {
            b.check_starts(slots, i);
            f.kind.body(&mut b, i, slots, rt);
            b.check_ends(slots, i);
        }
        b.sequenced |= !pads_fold(slots);
        if !b.sequenced {
            b.inline_reads(slots, rt);
        }
        b
    }

    /// A field read into a local and written from `self`: what most kinds add.
    pub(crate) fn value<K: Kind + ?Sized>(&mut self, kind: &K, id: &Ident, rt: &TokenStream) {
        self.sequenced |= kind.needs_locals();
        self.writes
            .push(kind.write(quote!(self.#id), &quote!(self), rt));
        let var = local(id);
        let read = kind.read(&quote!(r), rt);
        self.reads.push(quote!(let #var = #read;));
        self.inits.push(quote!(#id: #var));
    }

    /// Where the checks whose covered fields start at field `i` begin: a copy of the reader,
    /// the writer's position.
    fn check_starts(&mut self, slots: &[Slot<'_>], i: usize) {
        for (k, f) in slots.iter().enumerate() {
            if let Some((first, _)) = f.kind.covers() {
                if first == i {
                    let start = format_ident!("check{k}_start");
                    self.reads.push(quote!(let #start = r.clone();));
                    self.writes.push(quote!(let #start = w.position();));
                    self.sequenced = true;
                }
            }
        }
    }

    /// Where the checks whose covered fields end at field `i` end: the position after it.
    fn check_ends(&mut self, slots: &[Slot<'_>], i: usize) {
        for (k, f) in slots.iter().enumerate() {
            if let Some((_, last)) = f.kind.covers() {
                if last == i {
                    let end = format_ident!("check{k}_end");
                    self.reads.push(quote!(let #end = r.position();));
                    self.writes.push(quote!(let #end = w.position();));
                }
            }
        }
    }

    /// Nothing but padding between the fields: each field read straight into the value, in
    /// order, the padding before it skipped by the read itself (`r.pad(3)?.f32_le()?`), and
    /// the padding after the last field once the value is built.
    fn inline_reads(&mut self, slots: &[Slot<'_>], rt: &TokenStream) {
        self.reads.clear();
        self.inits.clear();
        let mut pad = 0usize;
        for f in slots {
            match (f.kind.padding(), &f.ident) {
                (Some(n), _) => pad += n,
                (None, Some(id)) => {
                    let read = match pad {
                        0 => f.kind.read(&quote!(r), rt),
                        n => f.kind.read(&quote!(r.pad(#n)?), rt),
                    };
                    pad = 0;
                    self.inits.push(quote!(#id: #read));
                }
                _ => {}
            }
        }
        if pad > 0 {
            self.after.push(quote!(r.skip(#pad)?;));
        }
    }
}

/// Whether the padding of `slots` can be skipped by the read of the field after it: that
/// field is read in one step (a single value, not an array, group or optional field).
fn pads_fold(slots: &[Slot<'_>]) -> bool {
    slots.windows(2).all(|pair| {
        pair[0].kind.padding().is_none()
            || pair[1].kind.padding().is_some()
            || pair[1].kind.folds_pad()
    })
}
