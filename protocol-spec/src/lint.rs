//! Lints: what compiles but is likely a risk on the wire, reported as warnings. A lint never
//! fails the macro or `protocol check` (the macro does not run them; the CLI prints them and
//! exits 0); every rule is a `check_*` function with its reason stated above it.

use crate::diag::{Diagnostic, Diagnostics};
use crate::ir::Protocol;
use crate::resources::{BUFFER_BOUND, needs, payload_span};
use crate::source::SpecSource;
use crate::spec::load_spec;
use crate::spec::model::SpecFile;

/// The lint warnings of a spec, sorted; none when it does not load (its errors come from
/// [`crate::compile`]).
pub fn lint(source: &SpecSource) -> Vec<Diagnostic> {
    let mut loading = Diagnostics::new();
    let Some(spec) = load_spec(source, &mut loading) else {
        return Vec::new();
    };
    let mut warnings = Diagnostics::new();
    check_frames_have_a_check(&spec, &mut warnings);
    if let Ok(protocol) = crate::compile(source) {
        check_decoder_buffer_bound(&spec, &protocol, &mut warnings);
    }
    warnings.into_sorted()
}

/// Rule: a generated decoder's buffer on a microcontroller stays within [`BUFFER_BOUND`]. A
/// frame format whose largest frame asks for more does not fit beside a firmware in the RAM of
/// many microcontrollers, and on a host it is most often a payload `max` far beyond what the
/// link sends (`docs/spec-format.md` gives the bound's reasons). Located at the payload, whose
/// `max` decides it.
fn check_decoder_buffer_bound(spec: &SpecFile, p: &Protocol, warnings: &mut Diagnostics) {
    for f in &p.frames {
        let needs = needs(f);
        if !needs.above_bound() {
            continue;
        }
        let Some((_, def)) = spec.frames.iter().find(|(n, _)| *n.get_ref() == f.name) else {
            continue;
        };
        warnings
            .warning(
                payload_span(def.get_ref()),
                format!(
                    "frame `{}` needs more than {} KiB of decoder buffer on a microcontroller: {}",
                    f.name,
                    BUFFER_BOUND / 1024,
                    needs.summary()
                ),
            )
            .help("lower the payload's `max` to the largest payload the link sends; see \"How much memory a decoder takes\" in docs/spec-format.md");
    }
}

/// Rule: a serial frame format has a check. Without one a decoder cannot reject a corrupt
/// candidate: a corrupt frame whose length field was hit is taken whole, and it can swallow
/// the start of the next valid frame. (A CAN frame is checked by the bus's own CRC.)
fn check_frames_have_a_check(spec: &SpecFile, warnings: &mut Diagnostics) {
    for (name, def) in &spec.frames {
        let f = def.get_ref();
        if f.transport.as_ref().is_some_and(|t| t.get_ref() == "can") {
            continue;
        }
        let checked = f
            .layout
            .get_ref()
            .iter()
            .any(|e| e.get_ref().check.is_some());
        if !checked {
            warnings
                .warning(
                    name.span(),
                    format!(
                        "frame `{}` has no check: a decoder cannot reject a corrupt frame, which can hide the next valid one",
                        name.get_ref()
                    ),
                )
                .help("add a check the link carries, such as `{ check = \"crc-16-ccitt-false\", over = \"frame\" }`; a link without one cannot be made safer here");
        }
    }
}
