//! Register values of a frame whose command selects registers (a spec's `[registers]` and a
//! command's `registers`): a WRITE's data typed by the registers it covers, and the answer to a
//! READ typed by the registers its request asked for (each answer to a SYNC_READ by the run the
//! request asked of every device, each to a BULK_READ by the run it asked of the answer's
//! sender). Where a register lies in the bytes is
//! the runtime's rule ([`Window::cover`]); its value is read as a struct field of its type.

use protocol_runtime::registers::{Cover, Window};
use protocol_spec::ir::{Protocol, Select};

use crate::Decoded;
use crate::model::{Fields, Value};
use crate::payload::read_register;

/// The registers a frame's bytes hold.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct RegisterValues {
    /// Every register the bytes hold whole, in address order.
    pub values: Fields,
    /// What the bytes hold that is not a whole register, or fall short of: a run that starts
    /// or ends inside a register, bytes at addresses of no register, an answer shorter than
    /// its request asked. `None` when every byte is a whole register's.
    pub note: Option<String>,
}

/// What a request selected, kept for its answers.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Selected {
    /// The request's command.
    pub command: usize,
    /// The runs it asked for: one that every answer carries, or, for a request that asks
    /// each device it lists a run of its own (a `BULK_READ`), one per listed device, in list
    /// order.
    pub runs: Vec<Run>,
}

/// A run of registers a request asked for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Run {
    /// The device asked, for a run of one listed device; `None` for a run every answer carries.
    pub device: Option<u8>,
    /// The first address.
    pub start: u32,
    /// The bytes it asked for (its `length` field), when the spec names one.
    pub asked: Option<u64>,
}

/// The select of `d`'s command, when it selects registers.
fn select_of<'p>(p: &'p Protocol, d: &Decoded) -> Option<&'p Select> {
    p.registers.as_ref()?.select(d.command?)
}

/// An integer field of a decoded payload.
fn uint(payload: &Value, name: &str) -> Option<u64> {
    match payload.get(name)? {
        Value::UInt(v) => Some(*v),
        Value::Int(v) => u64::try_from(*v).ok(),
        _ => None,
    }
}

/// What request `d` selects for its answers, when its command reads registers.
pub fn selected(p: &Protocol, d: &Decoded) -> Option<Selected> {
    let s = select_of(p, d)?;
    s.answer.as_ref()?;
    let runs = match &s.each {
        None => vec![run(s, &d.payload, None)?],
        Some(each) => {
            let Value::Array(elements) = d.payload.get(&each.group)? else {
                return None;
            };
            elements
                .iter()
                .filter_map(|e| {
                    let id = u8::try_from(uint(e, &each.id)?).ok()?;
                    run(s, e, Some(id))
                })
                .collect()
        }
    };
    Some(Selected {
        command: d.command?,
        runs,
    })
}

/// The run that the fields of `s` select in `of` (the request's payload, or one element of
/// its group for `device`).
fn run(s: &Select, of: &Value, device: Option<u8>) -> Option<Run> {
    let start = u32::try_from(uint(of, &s.address)?).ok()?;
    let asked = match &s.length {
        Some(l) => Some(uint(of, l)?),
        None => None,
    };
    Some(Run {
        device,
        start,
        asked,
    })
}

/// The run answer `d` carries: the one every answer carries, or the first of its sender's
/// (the answer's `answers.by` header value), as a device listed twice answers once.
fn run_of_answer(p: &Protocol, sel: &Selected, d: &Decoded) -> Option<Run> {
    let first = sel.runs.first()?;
    if first.device.is_none() {
        return Some(*first);
    }
    let fanout = p
        .session
        .as_ref()?
        .fanouts
        .iter()
        .find(|f| f.command == sel.command)?;
    let id = match d.header.get(&fanout.names.1)? {
        Value::UInt(v) => u8::try_from(*v).ok()?,
        _ => return None,
    };
    sel.runs.iter().find(|r| r.device == Some(id)).copied()
}

/// The registers request `d`'s data writes, when its command writes registers.
pub fn of_request(p: &Protocol, d: &Decoded) -> Option<RegisterValues> {
    let s = select_of(p, d)?;
    let start = u32::try_from(uint(&d.payload, &s.address)?).ok()?;
    let Value::Bytes(data) = d.payload.get(s.data.as_deref()?)? else {
        return None;
    };
    Some(values(p, Window::new(start, data)))
}

/// The registers answer `d` carries for the request that selected `sel`.
/// For a request that asks each listed device a run of its own, the run of the answer's
/// sender; an answer from a device the request does not list carries no registers.
pub fn of_answer(p: &Protocol, sel: &Selected, d: &Decoded) -> Option<RegisterValues> {
    let map = p.registers.as_ref()?;
    let (_, field) = map.select(sel.command)?.answer.as_ref()?;
    let Value::Bytes(data) = d.payload.get(field)? else {
        return None;
    };
    let run = run_of_answer(p, sel, d)?;
    let window = match run.asked {
        Some(asked) => Window::asked(run.start, asked, data),
        None => Window::new(run.start, data),
    };
    let mut v = values(p, window);
    if let Some(asked) = run.asked.filter(|&a| a > data.len() as u64) {
        let short = format!(
            "the answer carries {} of the {asked} bytes asked",
            data.len()
        );
        v.note = Some(match v.note {
            Some(n) => format!("{n}; {short}"),
            None => short,
        });
    }
    Some(v)
}

/// The registers in `window`, and a note of what is not whole.
fn values(p: &Protocol, window: Window<'_>) -> RegisterValues {
    let mut out = RegisterValues::default();
    let Some(map) = p.registers.as_ref() else {
        return out;
    };
    let mut notes = Vec::new();
    let mut covered = 0usize;
    for r in &map.registers {
        match window.cover(r.address, r.size) {
            Cover::Whole(bytes) => {
                if let Some(v) = read_register(&r.ty, bytes) {
                    out.values.insert(r.name.clone(), v);
                    covered += r.size;
                }
            }
            Cover::Part => {
                covered += part(window, r.address, r.size);
                notes.push(format!(
                    "holds part of `{}` ({} bytes at {})",
                    r.name, r.size, r.address
                ));
            }
            Cover::Outside => {}
        }
    }
    let unmapped = window.bytes().len().saturating_sub(covered);
    if unmapped > 0 {
        notes.push(format!("{unmapped} bytes at addresses of no register"));
    }
    if !notes.is_empty() {
        out.note = Some(notes.join("; "));
    }
    out
}

/// The bytes of a register that a window holds part of.
fn part(window: Window<'_>, address: u32, size: usize) -> usize {
    let first = u64::from(address).max(u64::from(window.start()));
    let last = (u64::from(address) + size as u64).min(window.end());
    usize::try_from(last.saturating_sub(first)).unwrap_or(0)
}
