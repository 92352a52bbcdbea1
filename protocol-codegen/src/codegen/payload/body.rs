//! The statements of one struct's `write` and `read`, field by field in wire order; each field
//! kind adds its own ([`Kind::body`]).

use proc_macro2::{Ident, TokenStream};
use quote::{format_ident, quote};

use super::kinds::{Kind, Slot, ok_of};
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
    /// The struct's name, for the field paths errors carry.
    pub(crate) owner: String,
}

impl Body {
    /// The statements of the struct `owner` (its name, for the field paths errors carry).
    pub(super) fn of(slots: &[Slot<'_>], owner: &str, rt: &TokenStream) -> Body {
        let mut b = Body {
            owner: owner.to_string(),
            ..Body::default()
        };
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
        let (mut write, mut read) = (
            kind.write(quote!(self.#id), &quote!(self), rt),
            kind.read(&quote!(r), rt),
        );
        if kind.value_can_fail() {
            write = write_in(&self.field_path(id), write, rt);
            read = read_in(&self.field_path(id), read, rt);
        }
        self.writes.push(write);
        let var = local(id);
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
                    let read = if f.kind.value_can_fail() {
                        read_in(&self.field_path(id), read, rt)
                    } else {
                        read
                    };
                    self.inits.push(quote!(#id: #read));
                }
                _ => {}
            }
        }
        if pad > 0 {
            self.after.push(quote!(r.skip(#pad)?;));
        }
    }

    /// The path an error names for field `id` of this struct: `Owner.field`, as the spec
    /// writes both.
    pub(crate) fn field_path(&self, id: &Ident) -> String {
        format!("{}.{}", self.owner, id.to_string().trim_start_matches("r#"))
    }
}

/// A field's read expression `read`, whose errors name the field `path`.
pub(crate) fn read_in(path: &str, read: TokenStream, rt: &TokenStream) -> TokenStream {
    let read = ok_of(read, rt);
    quote!(#rt::read_field(#path, || #read)?)
}

/// A field's write statements `write`, whose errors name the field `path`.
pub(crate) fn write_in(path: &str, write: TokenStream, rt: &TokenStream) -> TokenStream {
    quote!(#rt::write_field(#path, || { #write #rt::Ok(()) })?;)
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
