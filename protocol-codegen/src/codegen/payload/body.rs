//! The statements of one struct's `write` and `read`, field by field in wire order.

use proc_macro2::{Ident, TokenStream};
use quote::{format_ident, quote};

use super::def::{BitType, PBit, PField, PKind};
use super::field::{fixed_size, ok_of, read_value, write_value};
use super::scalar::{local, prim_type, read_elem, read_scalar, write_scalar};
use crate::ir::{ByteOrder, Prim, Scalar};

/// The code of one struct's `write` and `read`, field by field in wire order.
#[derive(Default)]
pub(super) struct Body {
    /// Statements of `write`.
    pub(super) writes: Vec<TokenStream>,
    /// Statements of `read` before the value is built.
    pub(super) reads: Vec<TokenStream>,
    /// `field: expression` of the value `read` builds.
    pub(super) inits: Vec<TokenStream>,
    /// Statements of `read` after the value is built (trailing padding).
    pub(super) after: Vec<TokenStream>,
    /// Whether a read expression needs an earlier field (sized bytes, groups), a statement
    /// comes between fields (a bit word) or padding comes before a field that is read in more
    /// than one step (an array): then every field is read into a local first.
    sequenced: bool,
}

impl Body {
    /// The statements of the struct `owner` (its name, for the field paths errors carry).
    pub(super) fn of(fields: &[PField], owner: &str, rt: &TokenStream) -> Body {
        let mut b = Body::default();
        for (i, f) in fields.iter().enumerate() {
            b.check_starts(fields, i);
            match &f.kind {
                PKind::Pad(n) => {
                    b.writes.push(quote!(w.zeros(#n)?;));
                    b.reads.push(quote!(r.skip(#n)?;));
                }
                PKind::Bits { word, members } => {
                    b.bits(&format_ident!("word{}", i), *word, members, owner, rt);
                    b.sequenced = true;
                }
                PKind::Check {
                    checksum, endian, ..
                } => {
                    let (start, end) = (
                        format_ident!("check{i}_start"),
                        format_ident!("check{i}_end"),
                    );
                    let order = match endian {
                        ByteOrder::Little => quote!(#rt::ByteOrder::Little),
                        ByteOrder::Big => quote!(#rt::ByteOrder::Big),
                    };
                    b.reads
                        .push(quote!(#rt::verify_check(r, &#start, #end, &#checksum, #order)?;));
                    b.writes
                        .push(quote!(#rt::put_check(w, #start, #end, &#checksum, #order)?;));
                }
                PKind::Bytes {
                    ty,
                    size_from: None,
                    ..
                } if i + 1 < fields.len() => {
                    // Every byte left but the checks after it.
                    let Some(id) = &f.ident else { continue };
                    let keep: usize = fields[i + 1..].iter().map(|f| fixed_size(&f.kind)).sum();
                    b.writes.push(quote!(self.#id.write(w)?;));
                    let var = local(id);
                    b.reads
                        .push(quote!(let #var = <#ty>::read_rest_but(r, #keep)?;));
                    b.inits.push(quote!(#id: #var));
                }
                kind => {
                    let Some(id) = &f.ident else { continue };
                    b.sequenced |= needs_locals(kind);
                    let (mut write, mut read) = (
                        write_value(kind, quote!(self.#id), &quote!(self), rt),
                        read_value(kind, rt),
                    );
                    if value_can_fail(kind) {
                        write = write_in(&field_path(owner, id), write, rt);
                        read = read_in(&field_path(owner, id), read, rt);
                    }
                    b.writes.push(write);
                    let var = local(id);
                    b.reads.push(quote!(let #var = #read;));
                    b.inits.push(quote!(#id: #var));
                }
            }
            b.check_ends(fields, i);
        }
        b.sequenced |= !pads_fold(fields);
        if !b.sequenced {
            b.inline_reads(fields, owner, rt);
        }
        b
    }

    /// Where the checks whose covered fields start at field `i` begin: a copy of the reader,
    /// the writer's position.
    fn check_starts(&mut self, fields: &[PField], i: usize) {
        for (k, f) in fields.iter().enumerate() {
            if let PKind::Check { first, .. } = f.kind {
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
    fn check_ends(&mut self, fields: &[PField], i: usize) {
        for (k, f) in fields.iter().enumerate() {
            if let PKind::Check { last, .. } = f.kind {
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
    fn inline_reads(&mut self, fields: &[PField], owner: &str, rt: &TokenStream) {
        self.reads.clear();
        self.inits.clear();
        let mut pad = 0usize;
        for f in fields {
            match (&f.kind, &f.ident) {
                (PKind::Pad(n), _) => pad += n,
                (kind, Some(id)) => {
                    let read = match pad {
                        0 => read_value(kind, rt),
                        n => read_elem(kind, &quote!(r.pad(#n)?), rt),
                    };
                    pad = 0;
                    let read = if value_can_fail(kind) {
                        read_in(&field_path(owner, id), read, rt)
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

    /// A bitfield word: each member set into (and got from) its bits by the runtime.
    fn bits(&mut self, var: &Ident, word: Scalar, members: &[PBit], owner: &str, rt: &TokenStream) {
        let wt = prim_type(word.prim);
        let mut sets = Vec::new();
        for m in members {
            let (id, shift, width) = (&m.ident, m.shift, m.width);
            let raw = match &m.ty {
                BitType::Bool => quote!(u64::from(self.#id)),
                BitType::Uint(_) => quote!(self.#id as u64),
                // Through the word type, as the word holds it (a signed raw value's bits).
                BitType::Enum(ty, _) => {
                    quote!(#rt::enum_raw(self.#id, #ty::to_raw, #ty::from_raw)? as #wt as u64)
                }
            };
            let path = field_path(owner, id);
            let set = quote!(#var = #rt::set_bits(#var, #raw, #shift, #width)?;);
            // A `bool` fits its bit; a wider value or an enum's raw value may not.
            sets.push(match m.ty {
                BitType::Bool => set,
                _ => write_in(&path, set, rt),
            });
            let field = quote!(#rt::get_bits(#var, #shift, #width));
            let value = match &m.ty {
                BitType::Bool => quote!(#field != 0),
                BitType::Uint(p) => {
                    let t = prim_type(*p);
                    quote!(#field as #t)
                }
                BitType::Enum(ty, p) => {
                    let t = prim_type(*p);
                    read_in(&path, quote!(#ty::from_raw(#field as #t)?), rt)
                }
            };
            self.inits.push(quote!(#id: #value));
        }
        self.writes.push(quote!(let mut #var = 0u64; #(#sets)*));
        self.writes.push(write_scalar(word, quote!(#var as #wt)));
        let read = read_scalar(word);
        self.reads.push(quote!(let #var = u64::from(#read);));
    }
}

/// The path an error names for field `id` of the struct `owner`: `Owner.field`, as the spec
/// writes both.
fn field_path(owner: &str, id: &Ident) -> String {
    format!("{owner}.{}", id.to_string().trim_start_matches("r#"))
}

/// Whether reading or writing a field of this kind can fail for its value (an enum value
/// without variant, a clamped or scaled value, a stated size, a 24-bit integer, text without
/// its NUL), not only for want of bytes or room: its code then names the field in the error.
/// A nested struct names its own fields.
fn value_can_fail(kind: &PKind) -> bool {
    match kind {
        PKind::Pad(_) | PKind::Nested { .. } | PKind::Check { .. } | PKind::Bits { .. } => false,
        PKind::Scalar { scalar, scale, .. } => {
            scale.is_some() || matches!(scalar.prim, Prim::U24 | Prim::I24)
        }
        PKind::Bytes { size_from, .. } => size_from.is_some(),
        PKind::Optional(inner) => value_can_fail(inner),
        PKind::Enum { .. }
        | PKind::Group { .. }
        | PKind::Array { .. }
        | PKind::Packed { .. }
        | PKind::Var { .. } => true,
    }
}

/// A field's read expression `read`, whose errors name the field `path`.
fn read_in(path: &str, read: TokenStream, rt: &TokenStream) -> TokenStream {
    let read = ok_of(read, rt);
    quote!(#rt::read_field(#path, || #read)?)
}

/// A field's write statements `write`, whose errors name the field `path`.
fn write_in(path: &str, write: TokenStream, rt: &TokenStream) -> TokenStream {
    quote!(#rt::write_field(#path, || { #write #rt::Ok(()) })?;)
}

/// Whether the padding of `fields` can be skipped by the read of the field after it: that
/// field is read in one step (a single value, not an array, group or optional field).
fn pads_fold(fields: &[PField]) -> bool {
    fields
        .windows(2)
        .all(|pair| match (&pair[0].kind, &pair[1].kind) {
            (PKind::Pad(_), PKind::Pad(_)) => true,
            (PKind::Pad(_), next) => {
                matches!(
                    next,
                    PKind::Scalar { count: None, .. }
                        | PKind::Nested { count: None, .. }
                        | PKind::Enum { count: None, .. }
                )
            }
            _ => true,
        })
}

/// Whether reading a field names an earlier field (sized bytes; a group, whose elements' sized
/// bytes may name the repeating struct's fields).
fn needs_locals(kind: &PKind) -> bool {
    match kind {
        PKind::Group { .. } => true,
        PKind::Bytes { size_from, .. } | PKind::Array { size_from, .. } => size_from.is_some(),
        PKind::Optional(inner) => needs_locals(inner),
        _ => false,
    }
}
