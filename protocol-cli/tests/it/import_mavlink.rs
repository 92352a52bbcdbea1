//! `protocol import mavlink`: the bundled `common` spec is what the importer writes from the
//! committed XML, its messages agree with the hand-typed `specs/mavlink.toml`, and the
//! importer's MAVLink rules (wire order, extensions, includes, enums merged across files,
//! bitmasks) hold on a small dialect.

use std::path::{Path, PathBuf};

use protocol_cli::import::mavlink::{crc_extra::crc_extra, import, model};
use toml::{Table, Value};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

fn spec(path: &str) -> Table {
    let text = std::fs::read_to_string(root().join(path)).expect(path);
    text.parse().expect(path)
}

#[test]
fn the_bundled_common_spec_is_what_the_importer_writes() {
    let written = import(&root().join("specs/mavlink-definitions/common.xml")).expect("import");
    let bundled = std::fs::read_to_string(root().join("specs/mavlink-common.toml")).unwrap();
    assert!(
        written == bundled,
        "specs/mavlink-common.toml differs from `protocol import mavlink \
         specs/mavlink-definitions/common.xml`: import it again"
    );
}

/// A field as the wire sees it: name, bytes, extension.
fn wire_fields(spec: &Table, name: &str) -> Vec<(String, usize, bool)> {
    let fields = spec["structs"][name]["fields"].as_array().expect(name);
    fields
        .iter()
        .map(|f| {
            let ty = f["type"].as_str().unwrap();
            let count = f.get("count").and_then(Value::as_integer).unwrap_or(1) as usize;
            let ext = f.get("extension").and_then(Value::as_bool).unwrap_or(false);
            (
                f["name"].as_str().unwrap().to_string(),
                type_size(spec, ty) * count,
                ext,
            )
        })
        .collect()
}

fn type_size(spec: &Table, ty: &str) -> usize {
    if let Some(n) = ty.strip_prefix("char[") {
        return n.trim_end_matches(']').parse().unwrap();
    }
    match ty {
        "u8" | "i8" => 1,
        "u16" | "i16" => 2,
        "u32" | "i32" | "f32" => 4,
        "u64" | "i64" | "f64" => 8,
        e => type_size(spec, spec["enums"][e]["type"].as_str().expect(e)),
    }
}

#[test]
fn the_hand_typed_messages_agree_with_the_imported_ones() {
    let hand = spec("specs/mavlink.toml");
    let imported = spec("specs/mavlink-common.toml");
    let commands = hand["commands"].as_table().unwrap();
    assert_eq!(commands.len(), 12);
    for (name, command) in commands {
        let other = &imported["commands"][name.as_str()];
        assert_eq!(command["id"], other["id"], "{name}: id");
        assert_eq!(
            command["check_extra"], other["check_extra"],
            "{name}: check_extra"
        );
        let payload = command["payload"].as_str().unwrap();
        assert_eq!(
            payload,
            other["payload"].as_str().unwrap(),
            "{name}: struct"
        );
        assert_eq!(
            wire_fields(&hand, payload),
            wire_fields(&imported, payload),
            "{name}: fields (name, bytes, extension) in wire order"
        );
    }
}

const INCLUDED: &str = r#"<?xml version="1.0"?>
<mavlink>
  <enums>
    <enum name="MODE">
      <description>A mode.</description>
      <entry value="0" name="MODE_OFF"><description>Off.</description></entry>
    </enum>
    <enum name="FLAGS" bitmask="true">
      <entry value="1" name="FLAG_A"/>
      <entry value="0x80" name="FLAG_H"/>
    </enum>
  </enums>
</mavlink>
"#;

const DIALECT: &str = r#"<?xml version="1.0"?>
<mavlink>
  <include>sub/included.xml</include>
  <enums>
    <enum name="MODE">
      <entry name="MODE_ON"><description>On &amp; running.</description></entry>
    </enum>
  </enums>
  <messages>
    <message id="300" name="PROBE_STATE">
      <description>A probe's state
        over two lines.</description>
      <field type="uint8_t" name="mode" enum="MODE">The mode.</field>
      <field type="uint16_t" name="flags" enum="FLAGS">Flags.</field>
      <field type="char[4]" name="tag">A tag.</field>
      <field type="float" name="zoomLevel" units="%">Zoom.</field>
      <field type="int16_t[3]" name="xyz" units="mm">A vector.</field>
      <extensions/>
      <field type="uint8_t" name="late">Added later.</field>
      <field type="double" name="later">Added later still.</field>
    </message>
  </messages>
</mavlink>
"#;

fn small_dialect() -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir(dir.path().join("sub")).unwrap();
    std::fs::write(dir.path().join("sub/included.xml"), INCLUDED).unwrap();
    std::fs::write(dir.path().join("probe.xml"), DIALECT).unwrap();
    dir
}

#[test]
fn fields_take_wire_order_and_includes_resolve_relative_to_the_file() {
    let dir = small_dialect();
    let dialect = model::load(&dir.path().join("probe.xml")).unwrap();
    assert_eq!(dialect.files, ["probe.xml", "included.xml"]);
    let m = &dialect.messages[0];
    let order: Vec<&str> = m.fields.iter().map(|f| f.name.as_str()).collect();
    // Base fields by element size, largest first, equal sizes in declared order; the
    // extensions after them as declared.
    assert_eq!(
        order,
        ["zoomLevel", "flags", "xyz", "mode", "tag", "late", "later"]
    );
    let mode = dialect.enum_named("MODE").unwrap();
    let values: Vec<(&str, u64)> = mode
        .entries
        .iter()
        .map(|e| (e.name.as_str(), e.value))
        .collect();
    assert_eq!(values, [("MODE_OFF", 0), ("MODE_ON", 1)]);
}

#[test]
fn crc_extra_hashes_the_base_fields_in_wire_order() {
    let dir = small_dialect();
    let dialect = model::load(&dir.path().join("probe.xml")).unwrap();
    let mut m = dialect.messages[0].clone();
    let extra = crc_extra(&m);
    // Extension fields take no part.
    m.fields.truncate(5);
    assert_eq!(crc_extra(&m), extra);
    // A base field's name, type or array length changes it.
    let mut renamed = m.clone();
    renamed.fields[0].name = "zoom".into();
    assert_ne!(crc_extra(&renamed), extra);
    let mut resized = m.clone();
    resized.fields[2].array = Some(4);
    assert_ne!(crc_extra(&resized), extra);
}

#[test]
fn the_spec_of_a_small_dialect_reads_as_the_importer_maps_it() {
    let dir = small_dialect();
    let text = import(&dir.path().join("probe.xml")).unwrap();
    let spec: Table = text.parse().expect("TOML");
    assert_eq!(spec["protocol"]["name"].as_str(), Some("mavlink_probe"));
    let command = &spec["commands"]["PROBE_STATE"];
    assert_eq!(command["id"].as_integer(), Some(300));
    assert_eq!(command["payload"].as_str(), Some("ProbeState"));
    assert_eq!(
        command["doc"].as_str(),
        Some("A probe's state over two lines.")
    );
    let fields = spec["structs"]["ProbeState"]["fields"].as_array().unwrap();
    let get = |i: usize, key: &str| fields[i].get(key).cloned();
    // camelCase becomes snake_case, the doc naming MAVLink's spelling.
    assert_eq!(get(0, "name"), Some("zoom_level".into()));
    assert_eq!(get(0, "unit"), Some("%".into()));
    assert!(
        get(0, "doc")
            .unwrap()
            .as_str()
            .unwrap()
            .contains("`zoomLevel`")
    );
    // A bitmask field is an integer; its bits are constants.
    assert_eq!(get(1, "type"), Some("u16".into()));
    assert_eq!(
        spec["constants"]["FLAG_H"]["value"].as_integer(),
        Some(0x80)
    );
    assert_eq!(get(2, "type"), Some("i16".into()));
    assert_eq!(get(2, "count"), Some(3.into()));
    // A plain enum types its field, and keeps values it does not know.
    assert_eq!(get(3, "type"), Some("Mode".into()));
    assert_eq!(spec["enums"]["Mode"]["type"].as_str(), Some("u8"));
    assert_eq!(spec["enums"]["Mode"]["unknown"].as_str(), Some("keep"));
    let on = &spec["enums"]["Mode"]["values"]["MODE_ON"];
    assert_eq!(on["doc"].as_str(), Some("On & running."));
    assert_eq!(get(4, "type"), Some("char[4]".into()));
    assert_eq!(get(5, "extension"), Some(true.into()));
    assert_eq!(get(6, "type"), Some("f64".into()));
    assert_eq!(
        spec["enums"].as_table().unwrap().len(),
        1,
        "no enum for a bitmask"
    );
}

#[test]
fn a_field_type_mavlink_does_not_have_is_an_error_naming_it() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("bad.xml");
    let xml = DIALECT
        .replace("int16_t[3]", "int24_t[3]")
        .replace("<include>sub/included.xml</include>", "");
    std::fs::write(&path, xml).unwrap();
    let err = import(&path).unwrap_err();
    assert!(err.contains("field xyz has type `int24_t[3]`"), "{err}");
    let missing = import(&dir.path().join("none.xml")).unwrap_err();
    assert!(missing.contains("cannot read"), "{missing}");
}
