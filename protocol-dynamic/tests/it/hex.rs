//! Hex text (`protocol decode --hex`, `bytes` fields): the separators it accepts, and where
//! it stops being hex.

use protocol_dynamic::{HexError, parse_hex, parse_hex_located};

#[test]
fn separators_and_prefixes_are_ignored() {
    let bytes = parse_hex_located("ff FF,0x01:0X1f\n  a5 5a\r\n").expect("hex");
    assert_eq!(bytes, [0xFF, 0xFF, 0x01, 0x1F, 0xA5, 0x5A]);
    assert_eq!(parse_hex(""), Some(Vec::new()));
}

#[test]
fn a_bad_digit_is_located() {
    assert_eq!(
        parse_hex_located("ff ff\n 01 0g"),
        Err(HexError {
            line: 2,
            column: 6,
            what: "`g` is not a hex digit".into()
        })
    );
    // `x` inside a word is no prefix.
    assert_eq!(
        parse_hex_located("1x").map_err(|e| (e.line, e.column)),
        Err((1, 2))
    );
    assert_eq!(parse_hex("ff zz"), None);
}

#[test]
fn an_unpaired_digit_is_located() {
    let e = parse_hex_located("ff\nff 0").expect_err("odd");
    assert_eq!((e.line, e.column), (2, 4));
    assert_eq!(
        e.to_string(),
        "line 2, column 4: the last hex digit has no pair (an odd number of digits)"
    );
}
