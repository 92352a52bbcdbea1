//! The rendered references in `docs/protocols/` are the current output of the docs generator
//! for every spec in `specs/`: CI fails when a spec or the generator changed and the docs were
//! not regenerated
//! (`UPDATE_DOCS=1 cargo test -p protocol-codegen --test it -- protocol_docs::`).

use std::path::Path;

use protocol_codegen::diag::render_all;
use protocol_codegen::source::SpecSource;

#[test]
fn rendered_docs_are_up_to_date() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let update = std::env::var_os("UPDATE_DOCS").is_some();
    let mut stale = Vec::new();
    let mut n = 0;
    let mut specs: Vec<_> = std::fs::read_dir(root.join("specs"))
        .expect("specs/")
        .map(|e| e.expect("entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    specs.sort();
    for path in specs {
        let stem = path
            .file_stem()
            .and_then(|s| s.to_str())
            .expect("name")
            .to_string();
        let text = std::fs::read_to_string(&path).expect("spec");
        let source = SpecSource::new(format!("specs/{stem}.toml"), text);
        let protocol = protocol_codegen::compile(&source)
            .unwrap_or_else(|d| panic!("{}", render_all(&d, &source)));
        let rendered = protocol_codegen::docs_md::render(&protocol);
        let doc = root.join("docs/protocols").join(format!("{stem}.md"));
        if update {
            std::fs::create_dir_all(doc.parent().expect("dir")).expect("docs/protocols");
            std::fs::write(&doc, &rendered).expect("write");
        } else if std::fs::read_to_string(&doc).ok().as_deref() != Some(rendered.as_str()) {
            stale.push(format!("docs/protocols/{stem}.md"));
        }
        n += 1;
    }
    assert!(n >= 6, "every reference protocol has a spec");
    assert!(
        stale.is_empty(),
        "stale rendered docs: {stale:?}; regenerate with `UPDATE_DOCS=1 cargo test -p protocol-codegen --test it -- protocol_docs::`"
    );
}
