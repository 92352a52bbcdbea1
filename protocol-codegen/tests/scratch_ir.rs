#[test]
fn scratch() {
    let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../specs/hflink.toml")).unwrap();
    let src = protocol_codegen::source::SpecSource::new("specs/hflink.toml", text);
    match protocol_codegen::compile(&src) {
        Ok(p) => { println!("{:#?}", p.frames); println!("{}", p.structs.iter().map(|s| format!("{} {}", s.name, s.size)).collect::<Vec<_>>().join(", ")); }
        Err(d) => println!("{}", protocol_codegen::diag::render_all(&d, &src)),
    }
}
