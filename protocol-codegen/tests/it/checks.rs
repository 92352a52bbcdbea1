//! What check names and custom checksums resolve to in the IR: catalogue aliases users know
//! name the catalogue entry itself, built-in sums and `[checksums]` sums are the runtime's own
//! algorithms, and a CRC's table lives in the `static` the IR names.

use protocol_codegen::ir::{Algorithm, CrcTable, Protocol};
use protocol_codegen::source::SpecSource;

/// A one-frame spec whose only check is `check` (plus extra `[checksums]` text).
fn spec_with(check: &str, checksums: &str) -> Protocol {
    spec_with_check_keys(check, "", checksums)
}

/// A one-frame spec whose only check is `check` with more keys (`keys`: `, table = 0`).
fn spec_with_check_keys(check: &str, keys: &str, checksums: &str) -> Protocol {
    let text = format!(
        r#"
[protocol]
name = "demo"

[frames.main]
layout = [
  {{ sync = [0xAA] }},
  {{ field = "length", type = "u8", length_of = "payload" }},
  {{ field = "command", type = "u8" }},
  {{ payload = {{ max = 16 }} }},
  {{ check = "{check}", over = "frame"{keys} }},
]
dispatch = ["command"]

[commands]
PING = {{ id = 1 }}
{checksums}
"#
    );
    let source = SpecSource::new("demo.toml", text);
    match protocol_codegen::compile(&source) {
        Ok(p) => p,
        Err(d) => panic!("{}", protocol_codegen::diag::render_all(&d, &source)),
    }
}

/// The catalogue constant a check name resolves to.
fn constant(check: &str) -> String {
    let p = spec_with(check, "");
    let c = &p.frames[0].checks[0];
    c.naming.crc_constant.clone().expect("a catalogue CRC")
}

#[test]
fn names_users_know_resolve_to_their_catalogue_entries() {
    for (name, want) in [
        ("CRC-16/CCITT-FALSE", "CRC_16_IBM_3740"),
        ("crc-16-ccitt-false", "CRC_16_IBM_3740"),
        ("CRC-16/XMODEM", "CRC_16_XMODEM"),
        ("CRC-16/MODBUS", "CRC_16_MODBUS"),
        ("CRC-16/KERMIT", "CRC_16_KERMIT"),
        ("CRC-16/CCITT", "CRC_16_KERMIT"),
        ("CRC-32", "CRC_32_ISO_HDLC"),
        ("crc32", "CRC_32_ISO_HDLC"),
        ("CRC-32C", "CRC_32_ISCSI"),
        ("CRC-8/DVB-S2", "CRC_8_DVB_S2"),
        ("CRC-16/X-25", "CRC_16_IBM_SDLC"),
        ("crc-16-umts", "CRC_16_UMTS"),
    ] {
        assert_eq!(constant(name), want, "{name}");
    }
}

#[test]
fn an_alias_computes_its_entrys_check_value() {
    let p = spec_with("CRC-16/CCITT-FALSE", "");
    match &p.frames[0].checks[0].algorithm {
        Algorithm::Crc16(spec) => {
            assert_eq!(spec.params, crc::CRC_16_IBM_3740);
            assert_eq!(spec.params.check, 0x29B1);
            assert_eq!(spec.table, CrcTable::ByTarget);
        }
        other => panic!("{other:?}"),
    }
    assert_eq!(
        p.frames[0].checks[0].naming.table_static.as_deref(),
        Some("CHECKSUM_TABLE")
    );
}

#[test]
fn built_in_sums_are_the_runtime_algorithms() {
    for (name, want, size) in [
        ("sum8", Algorithm::Sum8, 1),
        ("sum-mod-255", Algorithm::SumMod255, 1),
        ("xor8", Algorithm::Xor8, 1),
        (
            "sum16",
            Algorithm::Sum {
                width: 2,
                init: 0,
                xorout: 0,
            },
            2,
        ),
        ("fletcher-16", Algorithm::Fletcher16, 2),
        ("fletcher-16-mod-256", Algorithm::Fletcher16Mod256, 2),
    ] {
        let p = spec_with(name, "");
        let c = &p.frames[0].checks[0];
        assert_eq!(c.algorithm, want, "{name}");
        assert_eq!(c.size, size, "{name}");
        assert_eq!(c.naming.table_static, None, "{name}");
        assert_eq!(p.frames[0].trailer_len, size, "{name}");
    }
}

#[test]
fn custom_sums_carry_their_width_and_xorout() {
    let p = spec_with(
        "dxl",
        "[checksums.dxl]\nsum = { width = 8, xorout = 0xFF }\n",
    );
    assert_eq!(
        p.frames[0].checks[0].algorithm,
        Algorithm::Sum {
            width: 1,
            init: 0,
            xorout: 0xFF
        }
    );
    let p = spec_with(
        "ibus",
        "[checksums.ibus]\nsum = { width = 16, xorout = 0xFFFF }\n",
    );
    let c = &p.frames[0].checks[0];
    assert_eq!(
        c.algorithm,
        Algorithm::Sum {
            width: 2,
            init: 0,
            xorout: 0xFFFF
        }
    );
    assert_eq!(c.size, 2);
    assert!(c.naming.custom);
}

#[test]
fn a_custom_crc_keeps_its_table_choice() {
    let p = spec_with(
        "mine",
        "[checksums.mine]\ncrc = { width = 8, poly = 0x07, init = 0, refin = false, refout = false, xorout = 0, check = 0xF4 }\ntable = 0\n",
    );
    let c = &p.frames[0].checks[0];
    assert_eq!(c.algorithm.crc_table(), Some(CrcTable::NoTable));
    assert_eq!(c.naming.crc_constant, None);
}

#[test]
fn a_check_sizes_a_catalogue_crcs_table_keeping_its_parameters() {
    for (table, want) in [
        (0, CrcTable::NoTable),
        (1, CrcTable::Table1),
        (16, CrcTable::Table16),
    ] {
        let p = spec_with_check_keys("crc-16-umts", &format!(", table = {table}"), "");
        match &p.frames[0].checks[0].algorithm {
            Algorithm::Crc16(spec) => {
                assert_eq!(spec.params, crc::CRC_16_UMTS, "table {table}");
                assert_eq!(spec.table, want, "table {table}");
            }
            other => panic!("{other:?}"),
        }
    }
}

#[test]
fn a_checks_table_overrides_a_custom_crcs() {
    let p = spec_with_check_keys(
        "mine",
        ", table = 1",
        "[checksums.mine]\ncrc = { width = 8, poly = 0x07, init = 0, refin = false, refout = false, xorout = 0, check = 0xF4 }\ntable = 0\n",
    );
    assert_eq!(
        p.frames[0].checks[0].algorithm.crc_table(),
        Some(CrcTable::Table1)
    );
}
