//! serde's wording of an ill-typed value (`invalid type: sequence, expected i64`, `expected
//! struct CrcDef`, `integer ... as i128`) said in the spec's words: the key, what it takes and
//! what was written, as TOML calls them (a table, an array, an integer, a string).

use super::KeyOf;

/// The message and help for serde's `invalid type: FOUND, expected WANTED` or `invalid value:
/// FOUND, expected WANTED`; `None` for any other message.
pub(super) fn wrong_value(message: &str, key: Option<&KeyOf>) -> Option<(String, String)> {
    let rest = message
        .strip_prefix("invalid type: ")
        .or_else(|| message.strip_prefix("invalid value: "))?;
    let (found, wanted) = rest.rsplit_once(", expected ")?;
    let wanted_words = expected(wanted);
    let found_words = written(found);
    let subject = match key {
        Some(k) if k.element => format!("each element of `{}`", k.name),
        Some(k) => format!("`{}`", k.name),
        None => "this value".to_string(),
    };
    if let Some(n) = integer_of(found).filter(|_| is_integer_type(wanted)) {
        return Some((
            format!("{subject} is {n}, beyond what a spec integer holds"),
            "a spec integer is a TOML integer: from -2^63 to 2^63 - 1 (0x7FFF_FFFF_FFFF_FFFF)"
                .to_string(),
        ));
    }
    let verb = if key.is_some_and(|k| k.element) {
        "is"
    } else {
        "takes"
    };
    let message = format!("{subject} {verb} {wanted_words}, not {found_words}");
    Some((message, help(key, wanted, found)))
}

/// The help line: a fix for the mistakes users make, else where the key is described.
fn help(key: Option<&KeyOf>, wanted: &str, found: &str) -> String {
    let name = key.map_or("", |k| k.name.as_str());
    let element = key.is_some_and(|k| k.element);
    match (name, wanted) {
        ("crc", "struct CrcDef") if found.starts_with("string") => {
            "a built-in CRC is named where it is used (`{ check = \"crc-32\", over = \"frame\" }` in the layout); under `[checksums.NAME]`, `crc = { width = 16, poly = 0x1021, init = 0xFFFF, refin = false, refout = false, xorout = 0, check = 0x29B1 }` defines one".to_string()
        }
        ("sum", "struct SumDef") => "write `sum = { width = 8, xorout = 0xFF }`".to_string(),
        ("xor", "struct XorDef") => "write `xor = { init = 0xFF }`".to_string(),
        (_, w) if element && is_integer_type(w) && found == "sequence" => format!(
            "`{name}` is one flat array of integers: write `{name} = [0xC8, 0xEA]`, not an array of arrays"
        ),
        _ => format!("see docs/spec-format.md for what `{name}` takes")
            .replace("what `` takes", "the type each key takes"),
    }
}

/// serde's name of the expected type, as the spec calls it.
fn expected(wanted: &str) -> String {
    match wanted {
        w if is_integer_type(w) => "an integer".into(),
        "a string" | "string" => "a string".into(),
        "a boolean" | "bool" => "`true` or `false`".into(),
        "a sequence" => "an array".into(),
        "a map" => "a table".into(),
        "f32" | "f64" => "a number".into(),
        "struct CrcDef" => {
            "a table of CRC parameters `{ width, poly, init, refin, refout, xorout, check }`".into()
        }
        "struct SumDef" => "a table of sum parameters `{ width, init, xorout }`".into(),
        "struct XorDef" => "a table of XOR parameters `{ init }`".into(),
        w if w.starts_with("struct ") || w.starts_with("a map") => "a table".into(),
        w => w.to_string(),
    }
}

/// serde's description of the value found, as the spec calls it.
fn written(found: &str) -> String {
    if let Some(s) = found.strip_prefix("string ") {
        return format!("the string {s}");
    }
    if let Some(n) = integer_of(found) {
        return format!("the integer {n}");
    }
    match found {
        "sequence" => "an array".into(),
        "map" => "a table".into(),
        f if f.starts_with("boolean") => {
            format!("`{}`", f.trim_start_matches("boolean ").trim_matches('`'))
        }
        f if f.starts_with("floating point") => {
            format!(
                "the number {}",
                f.trim_start_matches("floating point ").trim_matches('`')
            )
        }
        f => f.to_string(),
    }
}

/// The digits of serde's `integer `N`` or `integer `N` as i128`.
fn integer_of(found: &str) -> Option<&str> {
    let rest = found.strip_prefix("integer `")?;
    rest.split('`').next()
}

fn is_integer_type(name: &str) -> bool {
    matches!(
        name,
        "i8" | "i16"
            | "i32"
            | "i64"
            | "i128"
            | "u8"
            | "u16"
            | "u32"
            | "u64"
            | "u128"
            | "usize"
            | "isize"
            | "an integer"
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn key(name: &str, element: bool) -> KeyOf {
        KeyOf {
            name: name.to_string(),
            element,
            array: None,
        }
    }

    #[test]
    fn serde_wording_becomes_the_spec_words() {
        // serde's two spellings of an integer that does not fit.
        for found in [
            "integer `18446744073709551615`",
            "integer `18446744073709551615` as i128",
        ] {
            let message = format!("invalid value: {found}, expected i64");
            let (said, help) = wrong_value(&message, Some(&key("id", false))).expect("handled");
            assert_eq!(
                said,
                "`id` is 18446744073709551615, beyond what a spec integer holds"
            );
            assert!(help.contains("2^63 - 1"), "{help}");
        }
        let (said, _) = wrong_value(
            "invalid type: sequence, expected i64",
            Some(&key("sync", true)),
        )
        .expect("handled");
        assert_eq!(said, "each element of `sync` is an integer, not an array");
        let (said, _) =
            wrong_value("invalid type: boolean `true`, expected a string", None).expect("handled");
        assert_eq!(said, "this value takes a string, not `true`");
        assert!(wrong_value("unknown variant `x`", None).is_none());
    }
}
